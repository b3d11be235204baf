// Thin strip 20 x 0.1 clamped on the left edge, one layer of 400 quadrilaterals: every bottom node is a candidate
// (401 of 802 nodes), so a dense Schur complement on the candidates would cost more than the sparse factorisation
// of this banded matrix (tests: reuse_factorization, the declined Schur complement).
// Physical groups: body, left (clamped edge), top, bottom, right.
L = 20; H = 0.1; h = 0.05;
Point(1) = {0, 0, 0, h}; Point(2) = {L, 0, 0, h}; Point(3) = {L, H, 0, h}; Point(4) = {0, H, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 401;
Transfinite Curve{2, 4} = 2;
Transfinite Surface{1};
Recombine Surface{1};
Physical Surface("body") = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
