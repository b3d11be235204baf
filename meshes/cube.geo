// Unit cube of hexahedra for the 3D rigid-plane case: graded towards x = 0 and y = 0 (progression 1.3), so the
// tributary areas of the bottom nodes differ. cube_tet.geo is the same cube in tetrahedra.
// Physical groups: body (volume), bottom (z = 0), top (z = 1), left (x = 0), front (y = 0) (surfaces).
L = 1; n = 5;
Point(1) = {0, 0, 0}; Point(2) = {L, 0, 0}; Point(3) = {L, L, 0}; Point(4) = {0, L, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {4, 3}; Line(4) = {1, 4};
Curve Loop(1) = {1, 2, -3, -4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = n + 1 Using Progression 1.3;
Transfinite Surface{1};
Recombine Surface{1};
out[] = Extrude {0, 0, L} { Surface{1}; Layers{4}; Recombine; };
Physical Volume("body") = {out[1]};
Physical Surface("bottom") = {1};
Physical Surface("top") = {out[0]};
Physical Surface("front") = {out[2]};
Physical Surface("left") = {out[5]};
