// Block of hexahedra (x in [-1, 1], y in [0, 1], z in [0, 0.5]) for the rigid-cylinder case: two transfinite halves
// mirrored about x = 0, graded towards x = 0 where the cylinder touches the bottom, so the mesh is symmetric about
// the plane through the cylinder's axis.
// Physical groups: body (volume), top (z = 0.5), bottom (z = 0), front (y = 0), top_centre (the top edge on x = 0).
W = 1; D = 1; H = 0.5;
nx = 12; ny = 4; nz = 4; grading = 0.85;
Point(1) = {-W, 0, 0}; Point(2) = {0, 0, 0}; Point(3) = {W, 0, 0};
Point(4) = {W, D, 0}; Point(5) = {0, D, 0}; Point(6) = {-W, D, 0};
Line(1) = {1, 2}; Line(2) = {3, 2}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {6, 5}; Line(6) = {1, 6};
Line(7) = {2, 5};
Curve Loop(1) = {1, 7, -5, -6};
Curve Loop(2) = {-2, 3, 4, -7};
Plane Surface(1) = {1};
Plane Surface(2) = {2};
// Each x-edge runs from the outer side to x = 0, so one progression gives mirrored node positions.
Transfinite Curve{1, 2, 4, 5} = nx + 1 Using Progression grading;
Transfinite Curve{3, 6, 7} = ny + 1;
Transfinite Surface{1, 2};
Recombine Surface{1, 2};
left[] = Extrude {0, 0, H} { Surface{1}; Layers{nz}; Recombine; };
right[] = Extrude {0, 0, H} { Surface{2}; Layers{nz}; Recombine; };
eps = 1e-6;
Physical Volume("body") = {left[1], right[1]};
Physical Surface("bottom") = {1, 2};
Physical Surface("top") = {left[0], right[0]};
Physical Surface("front") = Surface In BoundingBox{-W - eps, -eps, -eps, W + eps, eps, H + eps};
Physical Curve("top_centre") = Curve In BoundingBox{-eps, -eps, H - eps, eps, D + eps, H + eps};
