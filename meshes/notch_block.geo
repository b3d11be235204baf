// Unit block for the block-in-a-notch case (options/block_in_notch.yml), held by contact alone: quadrilaterals, with a
// corner point "anchor" (top left) for the comparison run that holds the block there by a Dirichlet condition.
// Physical groups: body (surface), bottom, top, left, right (curves), anchor (point).
h = 0.1;
Point(1) = {0, 0, 0, h}; Point(2) = {1, 0, 0, h}; Point(3) = {1, 1, 0, h}; Point(4) = {0, 1, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = 11;
Transfinite Surface{1};
Recombine Surface{1};
Physical Surface("body") = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Point("anchor") = {4};
