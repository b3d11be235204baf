// Block 2 x 1 for the rigid-floor, corner and file-format cases: a mixed mesh, quadrilaterals on the left half (graded,
// finer towards the left edge) and triangles on the right half (finer towards the lower right corner), so that the
// tributary lengths of the bottom nodes differ. block.msh (4.1 ASCII), block_bin.msh (4.1 binary, gmsh -bin) and
// block_v22.msh (2.2 ASCII, gmsh -format msh22) are the same mesh.
// Physical groups: body (surface), bottom, top, left, right (curves).
W = 2; H = 1; h = 0.125;
Point(1) = {0, 0, 0, h}; Point(2) = {W / 2, 0, 0, h}; Point(3) = {W, 0, 0, 0.6 * h};
Point(4) = {W, H, 0, h}; Point(5) = {W / 2, H, 0, h}; Point(6) = {0, H, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6}; Line(6) = {6, 1};
Line(7) = {2, 5};
Curve Loop(1) = {1, 7, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7};
Plane Surface(2) = {2};
Transfinite Curve{1} = 9 Using Progression 1.15;
Transfinite Curve{5} = 9 Using Progression 1 / 1.15;
Transfinite Curve{6, 7} = 6;
Transfinite Surface{1};
Recombine Surface{1};
Physical Surface("body") = {1, 2};
Physical Curve("bottom") = {1, 2};
Physical Curve("right") = {3};
Physical Curve("top") = {4, 5};
Physical Curve("left") = {6};
