// 3D Hertz contact of two bodies: the lower octant (x >= 0, y >= 0, z <= 0) of a ball of radius R = 10 centred at
// the origin resting on a block (a quarter, 0 <= x, y <= 6, -16 <= z <= -10) that it touches at (0, 0, -10). The
// planes x = 0 and y = 0 are symmetry planes, so the model is a quarter of the ball on the block. The two volumes
// keep their own faces and nodes (no boolean fragments), so the bodies share no nodes. The ball (the slave side) is
// refined more finely near the contact than the block; scale every size with -mesh_size_factor (or gmsh -clscale).
// Physical groups: ball, block (volumes); top (z = 0), contact (the spherical surface), block_top (z = -10),
// block_bottom (z = -16), symmetry_x, symmetry_y (both bodies' faces on x = 0 and y = 0).
SetFactory("OpenCASCADE");
R = 10; B = 6;
h_far = 2.5;
h_ball = 0.08;
h_block = 0.12;
Sphere(1) = {0, 0, 0, R, -Pi / 2, 0, Pi / 2};
Box(2) = {0, 0, -R - B, B, B, B};
eps = 1e-6 * R;
top() = Surface In BoundingBox{-eps, -eps, -eps, R + eps, R + eps, eps};
sx1() = Surface In BoundingBox{-eps, -eps, -R - eps, eps, R + eps, eps};
sy1() = Surface In BoundingBox{-eps, -eps, -R - eps, R + eps, eps, eps};
contact() = Boundary{Volume{1};};
contact() -= top();
contact() -= sx1();
contact() -= sy1();
sx2() = Surface In BoundingBox{-eps, -eps, -R - B - eps, eps, B + eps, -R + eps};
sy2() = Surface In BoundingBox{-eps, -eps, -R - B - eps, B + eps, eps, -R + eps};
block_top() = Surface In BoundingBox{-eps, -eps, -R - eps, B + eps, B + eps, -R + eps};
block_bottom() = Surface In BoundingBox{-eps, -eps, -R - B - eps, B + eps, B + eps, -R - B + eps};
ball_point() = Point In BoundingBox{-eps, -eps, -R - eps, eps, eps, -R + eps};
ball_point() -= PointsOf{Volume{2};};
block_point() = Point In BoundingBox{-eps, -eps, -R - eps, eps, eps, -R + eps};
block_point() -= ball_point();

Field[1] = Distance;
Field[1].PointsList = {ball_point()};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h_ball;
Field[2].SizeMax = h_far;
Field[2].DistMin = 1.5;
Field[2].DistMax = 8.0;
Field[3] = Restrict;
Field[3].InField = 2;
Field[3].VolumesList = {1};
Field[3].SurfacesList = {Abs(Boundary{Volume{1};})};
Field[3].CurvesList = {Unique(Abs(Boundary{Boundary{Volume{1};}}))};
Field[4] = Distance;
Field[4].PointsList = {block_point()};
Field[5] = Threshold;
Field[5].InField = 4;
Field[5].SizeMin = h_block;
Field[5].SizeMax = h_far;
Field[5].DistMin = 1.5;
Field[5].DistMax = 8.0;
Field[6] = Restrict;
Field[6].InField = 5;
Field[6].VolumesList = {2};
Field[6].SurfacesList = {Abs(Boundary{Volume{2};})};
Field[6].CurvesList = {Unique(Abs(Boundary{Boundary{Volume{2};}}))};
Field[7] = Min;
Field[7].FieldsList = {3, 6};
Background Field = 7;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;

Physical Volume("ball") = {1};
Physical Volume("block") = {2};
Physical Surface("top") = {top()};
Physical Surface("contact") = {contact()};
Physical Surface("block_top") = {block_top()};
Physical Surface("block_bottom") = {block_bottom()};
Physical Surface("symmetry_x") = {sx1(), sx2()};
Physical Surface("symmetry_y") = {sy1(), sy2()};
