// Two blocks that share no node, one above the other: [0, 1] x [0, 1] (lower, triangles) and [0.2, 0.8] x [1.5, 2]
// (upper, quadrilaterals), each clamped at its bottom: two bodies of one mesh (tests/cases, two_bodies).
// Physical groups: lower, upper (cells), lower_bottom, upper_bottom, lower_top, upper_top.
h = 0.125;
Point(1) = {0, 0, 0, h}; Point(2) = {1, 0, 0, h}; Point(3) = {1, 1, 0, h}; Point(4) = {0, 1, 0, h};
Point(5) = {0.2, 1.5, 0, h}; Point(6) = {0.8, 1.5, 0, h}; Point(7) = {0.8, 2, 0, h}; Point(8) = {0.2, 2, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(2) = {2};
Transfinite Curve{5, 6, 7, 8} = 5;
Transfinite Surface{2};
Recombine Surface{2};
Physical Surface("lower") = {1};
Physical Surface("upper") = {2};
Physical Curve("lower_bottom") = {1};
Physical Curve("lower_top") = {3};
Physical Curve("upper_bottom") = {5};
Physical Curve("upper_top") = {7};
