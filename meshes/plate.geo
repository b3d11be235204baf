// Plate 6 x 2 for the clamped-plate-over-an-arc case (options/plate_on_arc.yml): the bottom edge is split at x = 2 into
// the clamped third ("clamp") and the free part ("bottom", the contact candidates).
// Physical groups: body (surface), clamp, bottom, top, left, right (curves).
W = 6; H = 2; h = 0.2;
Point(1) = {0, 0, 0, h}; Point(2) = {2, 0, 0, h}; Point(3) = {W, 0, 0, h};
Point(4) = {W, H, 0, h}; Point(5) = {0, H, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 1};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Physical Surface("body") = {1};
Physical Curve("clamp") = {1};
Physical Curve("bottom") = {2};
Physical Curve("right") = {3};
Physical Curve("top") = {4};
Physical Curve("left") = {5};
