// Cattaneo-Mindlin partial slip (3D): two equal balls of radius R = 10, mirror images of each other about z = 0,
// touching at the origin: the lower half of the upper ball (centre (0, 0, R)) and the upper half of the lower ball
// (centre (0, 0, -R)), each cut to y >= 0 (the plane y = 0 is a symmetry plane of a load in the x-z plane). Each body
// keeps its own faces and nodes. The upper one is the slave side (finer near the contact); scale every size with
// -mesh_size_factor (or gmsh -clscale).
// Physical groups: upper, lower (volumes); upper_top (z = R), upper_contact, lower_contact (the spherical surfaces),
// lower_bottom (z = -R), symmetry_y (both bodies' faces on y = 0).
SetFactory("OpenCASCADE");
R = 10;
h_far = 2.5;
h_slave = 0.12;
h_master = 0.18;
Sphere(1) = {0, 0, R, R, -Pi / 2, 0, Pi};
Sphere(2) = {0, 0, -R, R, 0, Pi / 2, Pi};
eps = 1e-6 * R;
top() = Surface In BoundingBox{-R - eps, -eps, R - eps, R + eps, R + eps, R + eps};
bottom() = Surface In BoundingBox{-R - eps, -eps, -R - eps, R + eps, R + eps, -R + eps};
sy1() = Surface In BoundingBox{-R - eps, -eps, -eps, R + eps, eps, R + eps};
sy2() = Surface In BoundingBox{-R - eps, -eps, -R - eps, R + eps, eps, eps};
upper_contact() = Boundary{Volume{1};};
upper_contact() -= top();
upper_contact() -= sy1();
lower_contact() = Boundary{Volume{2};};
lower_contact() -= bottom();
lower_contact() -= sy2();
upper_point() = Point In BoundingBox{-eps, -eps, -eps, eps, eps, eps};
upper_point() -= PointsOf{Volume{2};};
lower_point() = Point In BoundingBox{-eps, -eps, -eps, eps, eps, eps};
lower_point() -= upper_point();
Field[1] = Distance;
Field[1].PointsList = {upper_point()};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h_slave;
Field[2].SizeMax = h_far;
Field[2].DistMin = 2.5;
Field[2].DistMax = 9.0;
Field[3] = Restrict;
Field[3].InField = 2;
Field[3].VolumesList = {1};
Field[3].SurfacesList = {Abs(Boundary{Volume{1};})};
Field[3].CurvesList = {Unique(Abs(Boundary{Boundary{Volume{1};}}))};
Field[4] = Distance;
Field[4].PointsList = {lower_point()};
Field[5] = Threshold;
Field[5].InField = 4;
Field[5].SizeMin = h_master;
Field[5].SizeMax = h_far;
Field[5].DistMin = 2.5;
Field[5].DistMax = 9.0;
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
Physical Volume("upper") = {1};
Physical Volume("lower") = {2};
Physical Surface("upper_top") = {top()};
Physical Surface("upper_contact") = {upper_contact()};
Physical Surface("lower_contact") = {lower_contact()};
Physical Surface("lower_bottom") = {bottom()};
Physical Surface("symmetry_y") = {sy1(), sy2()};
