// Quarter of a square plate 2 x 2 x 0.25 (x, y in [0, 1], z in [0, 0.25]) of hexahedra for options/punch_on_plate.yml,
// graded towards the punch's axis x = y = 0 (progression 1.2 from about 0.014 at the axis).
// Physical groups: body (volume), bottom (z = 0), top (z = 0.25), left (x = 0), front (y = 0) (surfaces).
L = 1; T = 0.25; n = 15;
Point(1) = {0, 0, 0}; Point(2) = {L, 0, 0}; Point(3) = {L, L, 0}; Point(4) = {0, L, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {4, 3}; Line(4) = {1, 4};
Curve Loop(1) = {1, 2, -3, -4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = n + 1 Using Progression 1.2;
Transfinite Surface{1};
Recombine Surface{1};
out[] = Extrude {0, 0, T} { Surface{1}; Layers{4}; Recombine; };
Physical Volume("body") = {out[1]};
Physical Surface("bottom") = {1};
Physical Surface("top") = {out[0]};
Physical Surface("front") = {out[2]};
Physical Surface("left") = {out[5]};
