// A block sliding along a floor (2D): the block [0, 1] x [0, 0.5] (quadrilaterals, 10 x 5) rests on a long floor
// [-1, 5] x [-0.5, 0] (quadrilaterals, 24 x 2, coarser), non-matching on their interface y = 0. The bodies share no
// nodes (the block has its own points on y = 0).
// Physical groups: block, floor (surfaces); block_bottom, block_top, block_left, floor_top, floor_bottom (curves).
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 0.5, 0}; Point(4) = {0, 0.5, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 11; Transfinite Curve{2, 4} = 6;
Transfinite Surface{1}; Recombine Surface{1};
Point(11) = {-1, -0.5, 0}; Point(12) = {5, -0.5, 0}; Point(13) = {5, 0, 0}; Point(14) = {-1, 0, 0};
Line(11) = {11, 12}; Line(12) = {12, 13}; Line(13) = {13, 14}; Line(14) = {14, 11};
Curve Loop(2) = {11, 12, 13, 14}; Plane Surface(2) = {2};
Transfinite Curve{11, 13} = 25; Transfinite Curve{12, 14} = 3;
Transfinite Surface{2}; Recombine Surface{2};
Physical Surface("block") = {1};
Physical Surface("floor") = {2};
Physical Curve("block_bottom") = {1};
Physical Curve("block_top") = {3};
Physical Curve("block_left") = {4};
Physical Curve("floor_top") = {13};
Physical Curve("floor_bottom") = {11};
