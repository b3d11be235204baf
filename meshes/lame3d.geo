// Lame thick spherical shell (inner radius 1, outer radius 2), octant x, y, z >= 0 with symmetry planes, tetrahedra.
// Physical groups: body (volume), inner (r = 1, the pressurised surface), outer (r = 2), symmetry_x (x = 0),
// symmetry_y (y = 0), symmetry_z (z = 0). Refine with -mesh_size_factor (or gmsh -clscale). lame3d_hex.geo is the
// same shell in hexahedra.
SetFactory("OpenCASCADE");
a = 1;
b = 2;
h = 0.25;
Sphere(1) = {0, 0, 0, b, 0, Pi / 2, Pi / 2};
Sphere(2) = {0, 0, 0, a, 0, Pi / 2, Pi / 2};
BooleanDifference(3) = {Volume{1}; Delete;}{Volume{2}; Delete;};
eps = 1e-6;
inner() = Surface In BoundingBox{-eps, -eps, -eps, a + eps, a + eps, a + eps};
sx() = Surface In BoundingBox{-eps, -eps, -eps, eps, b + eps, b + eps};
sy() = Surface In BoundingBox{-eps, -eps, -eps, b + eps, eps, b + eps};
sz() = Surface In BoundingBox{-eps, -eps, -eps, b + eps, b + eps, eps};
outer() = Boundary{Volume{3};};
outer() -= inner();
outer() -= sx();
outer() -= sy();
outer() -= sz();
MeshSize{PointsOf{Volume{3};}} = h;
Physical Volume("body") = {3};
Physical Surface("inner") = {inner()};
Physical Surface("outer") = {outer()};
Physical Surface("symmetry_x") = {sx()};
Physical Surface("symmetry_y") = {sy()};
Physical Surface("symmetry_z") = {sz()};
