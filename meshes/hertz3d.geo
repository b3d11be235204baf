// 3D Hertz benchmark: the lower octant (x >= 0, y >= 0, z <= 0) of a ball of radius R = 10 centred at the origin,
// whose lowest point (0, 0, -R) touches a rigid plane z = -R. The load is a uniform pressure on the flat top z = 0;
// the planes x = 0 and y = 0 are symmetry planes (u_x = 0 and u_y = 0), so the model is a quarter of the
// hemisphere and carries a quarter of its load.
// Physical groups: body (volume), top (z = 0), symmetry_x (x = 0), symmetry_y (y = 0), contact (the spherical
// surface) and contact_point (the lowest point).
// Graded towards the contact point: h_contact within DistMin of it, growing to h_far at DistMax; the contact radius
// of options/hertz3d.yml is a = 0.8. Scale every size with -mesh_size_factor (or gmsh -clscale); hertz3d.msh is
// factor 1.4.
SetFactory("OpenCASCADE");
R = 10;
h_far = 2.5;
h_contact = 0.04;
Sphere(1) = {0, 0, 0, R, -Pi / 2, 0, Pi / 2};
eps = 1e-6 * R;
top() = Surface In BoundingBox{-eps, -eps, -eps, R + eps, R + eps, eps};
sx() = Surface In BoundingBox{-eps, -eps, -R - eps, eps, R + eps, eps};
sy() = Surface In BoundingBox{-eps, -eps, -R - eps, R + eps, eps, eps};
all() = Boundary{Volume{1};};
contact() = all();
contact() -= top();
contact() -= sx();
contact() -= sy();
bottom() = Point In BoundingBox{-eps, -eps, -R - eps, eps, eps, -R + eps};

Field[1] = Distance;
Field[1].PointsList = {bottom()};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h_contact;
Field[2].SizeMax = h_far;
Field[2].DistMin = 1.2;
Field[2].DistMax = 8.0;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;

Physical Volume("body") = {1};
Physical Surface("top") = {top()};
Physical Surface("symmetry_x") = {sx()};
Physical Surface("symmetry_y") = {sy()};
Physical Surface("contact") = {contact()};
Physical Point("contact_point") = {bottom()};
