// A concave rigid corner for the unit cube of meshes/cube.geo, as a meshed obstacle (-obstacle_mesh): the floor
// z = 0 and the walls x = 0 and y = 0, each the square [0, 1.25]^2 in its plane as 3 x 3 quadrilaterals, oriented so
// that every right-hand normal points into the octant x, y, z > 0 (the body); the three faces meet along the axes,
// where each edge is traversed in opposite directions by its two faces. Physical surface "corner".
a = 1.25;
Point(1) = {0, 0, 0}; Point(2) = {a, 0, 0}; Point(3) = {0, a, 0}; Point(4) = {0, 0, a};
Point(5) = {a, a, 0}; Point(6) = {0, a, a}; Point(7) = {a, 0, a};
Line(1) = {1, 2}; Line(2) = {1, 3}; Line(3) = {1, 4};
Line(4) = {2, 5}; Line(5) = {5, 3}; Line(6) = {3, 6}; Line(7) = {6, 4}; Line(8) = {4, 7}; Line(9) = {7, 2};
Curve Loop(1) = {1, 4, 5, -2}; Plane Surface(1) = {1}; // floor, normal +z
Curve Loop(2) = {2, 6, 7, -3}; Plane Surface(2) = {2}; // wall x = 0, normal +x
Curve Loop(3) = {3, 8, 9, -1}; Plane Surface(3) = {3}; // wall y = 0, normal +y
Transfinite Curve{1 : 9} = 4;
Transfinite Surface{1 : 3};
Recombine Surface{1 : 3};
Physical Surface("corner") = {1 : 3};
