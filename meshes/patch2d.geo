// Contact patch test (2D): two blocks 2 x 1 stacked with a flat interface at y = 1 and non-matching meshes on its
// two sides (the lower block coarse, the upper one finer and graded, so that no node of one side lies over a node of
// the other but the ends). The bodies share no nodes: each block has its own points on the interface.
// -setnumber quads 1 recombines both blocks into quadrilaterals; 0 (the default) leaves triangles. -setnumber gap G
// lifts the upper block by G (the interface is open at the start; patch2d_gap.msh: G = 0.01).
// Physical groups: lower, upper (surfaces); bottom, lower_top, lower_left, upper_bottom, upper_top, upper_left
// (curves).
DefineConstant[quads = 0, gap = 0];
W = 2; H = 1;
Point(1) = {0, 0, 0}; Point(2) = {W, 0, 0}; Point(3) = {W, H, 0}; Point(4) = {0, H, 0};
Point(5) = {0, H + gap, 0}; Point(6) = {W, H + gap, 0}; Point(7) = {W, 2 * H + gap, 0}; Point(8) = {0, 2 * H + gap, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};
Transfinite Curve{1, 3} = 6;
Transfinite Curve{2, 4} = 4;
Transfinite Curve{5} = 10 Using Progression 1.12;
Transfinite Curve{7} = 10 Using Progression 1 / 1.12;
Transfinite Curve{6, 8} = 5;
Transfinite Surface{1}; Transfinite Surface{2};
If (quads)
  Recombine Surface{1, 2};
EndIf
Physical Surface("lower") = {1};
Physical Surface("upper") = {2};
Physical Curve("bottom") = {1};
Physical Curve("lower_top") = {3};
Physical Curve("lower_left") = {4};
Physical Curve("upper_bottom") = {5};
Physical Curve("upper_top") = {7};
Physical Curve("upper_left") = {8};
