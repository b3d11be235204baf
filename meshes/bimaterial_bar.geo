// Bar of two materials in series, [0, 1.2] x [0, 0.4] (soft, triangles) and [1.2, 2] x [0, 0.4] (stiff,
// quadrilaterals), one connected body: under a traction on its right end, with the left end on rollers, the end
// displacement is t (L1 / E1 + L2 / E2) exactly for nu = 0 (tests/cases, bimaterial_bar).
// Physical groups: soft, stiff, all (both surfaces: a doubly covered cell for the bad-input catalogue), left, right,
// origin (the point that fixes y).
h = 0.1;
Point(1) = {0, 0, 0, h}; Point(2) = {1.2, 0, 0, h}; Point(3) = {2, 0, 0, h};
Point(4) = {2, 0.4, 0, h}; Point(5) = {1.2, 0.4, 0, h}; Point(6) = {0, 0.4, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 5}; Line(3) = {5, 6}; Line(4) = {6, 1};
Line(5) = {2, 3}; Line(6) = {3, 4}; Line(7) = {4, 5};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, -2};
Plane Surface(2) = {2};
Transfinite Curve{5, 7} = 9;
Transfinite Curve{2, 6} = 5;
Transfinite Surface{2};
Recombine Surface{2};
Physical Surface("soft") = {1};
Physical Surface("stiff") = {2};
Physical Surface("all") = {1, 2};
Physical Curve("left") = {4};
Physical Curve("right") = {6};
Physical Point("origin") = {1};
