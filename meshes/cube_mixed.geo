// Two unit cubes in one mesh for the mixed-cell case: the hexahedra of cube.geo (x in [0, 1]) and a cube of
// tetrahedra at x in [2, 3], finer towards its corner (3, 1, 0). They do not touch (a shared face of
// quadrilaterals against triangles would not be conforming; cube_mixed_conforming.geo joins a tetrahedral half to
// the hexahedra with pyramids).
// Physical groups as in cube.geo, each covering both cubes: body, bottom (z = 0), top (z = 1), left (x = 0 and
// x = 2), front (y = 0).
Include "cube.geo";
Point(101) = {2, 0, 0, 0.3}; Point(102) = {3, 0, 0, 0.3}; Point(103) = {3, 1, 0, 0.12}; Point(104) = {2, 1, 0, 0.3};
Line(101) = {101, 102}; Line(102) = {102, 103}; Line(103) = {104, 103}; Line(104) = {101, 104};
Curve Loop(101) = {101, 102, -103, -104};
Plane Surface(101) = {101};
tet[] = Extrude {0, 0, 1} { Surface{101}; };
Physical Volume("body") += {tet[1]};
Physical Surface("bottom") += {101};
Physical Surface("top") += {tet[0]};
Physical Surface("front") += {tet[2]};
Physical Surface("left") += {tet[5]};
