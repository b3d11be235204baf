// Hertz benchmark: the lower half of a cylinder of radius R = 8 (centre at the origin) whose lowest point (0,-R)
// touches a rigid flat at y = -R. Plane strain; the load is a uniform traction on the flat top edge.
// Physical groups: body (surface), top (loaded edge), contact (the curved edge), top_centre and contact_point (the
// points on the symmetry line, u_x = 0: with the first contact they hold every rigid-body motion).
// Refined near the contact point; scale every size with -mesh_size_factor (or gmsh -clscale).
R = 8;
h_far = 0.8;
h_contact = 0.02;
Point(1) = {0, 0, 0, h_far};
Point(2) = {-R, 0, 0, h_far};
Point(3) = {R, 0, 0, h_far};
Point(4) = {0, -R, 0, h_contact};
Line(1) = {2, 1};
Line(2) = {1, 3};
Circle(3) = {3, 1, 4};
Circle(4) = {4, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

Field[1] = Distance;
Field[1].PointsList = {4};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h_contact;
Field[2].SizeMax = h_far;
Field[2].DistMin = 1.0;
Field[2].DistMax = 6.0;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;

Physical Surface("body") = {1};
Physical Curve("top") = {1, 2};
Physical Curve("contact") = {3, 4};
Physical Point("top_centre") = {1};
Physical Point("contact_point") = {4};
