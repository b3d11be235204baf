// Hertz contact of two cylinders (2D, plane strain): the lower half of a cylinder of radius R1 = 8 (centre (0, R1))
// resting on the upper half of a cylinder of radius R2 = 12 (centre (0, -R2)); they touch at the origin. Two bodies
// that share no nodes (each has its own point at the origin). The upper body is refined more finely near the contact
// (its edge is the slave side); scale every size with -mesh_size_factor (or gmsh -clscale).
// Physical groups: upper, lower (surfaces); upper_top, upper_contact, lower_contact, lower_bottom (curves);
// upper_top_centre, upper_contact_point, lower_contact_point, lower_bottom_centre (points on the symmetry line).
R1 = 8; R2 = 12;
h_far = 0.8;
h_slave = 0.02;
h_master = 0.03;
Point(1) = {0, R1, 0, h_far}; Point(2) = {-R1, R1, 0, h_far}; Point(3) = {R1, R1, 0, h_far};
Point(4) = {0, 0, 0, h_slave};
Line(1) = {2, 1}; Line(2) = {1, 3};
Circle(3) = {3, 1, 4}; Circle(4) = {4, 1, 2};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Point(11) = {0, -R2, 0, h_far}; Point(12) = {R2, -R2, 0, h_far}; Point(13) = {-R2, -R2, 0, h_far};
Point(14) = {0, 0, 0, h_master};
Line(11) = {13, 11}; Line(12) = {11, 12};
Circle(13) = {12, 11, 14}; Circle(14) = {14, 11, 13};
Curve Loop(2) = {-14, -13, -12, -11}; Plane Surface(2) = {2}; // clockwise, as the upper loop

Field[1] = Distance;
Field[1].PointsList = {4};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h_slave;
Field[2].SizeMax = h_far;
Field[2].DistMin = 1.0;
Field[2].DistMax = 6.0;
Field[3] = Distance;
Field[3].PointsList = {14};
Field[4] = Threshold;
Field[4].InField = 3;
Field[4].SizeMin = h_master;
Field[4].SizeMax = h_far;
Field[4].DistMin = 1.0;
Field[4].DistMax = 6.0;
Field[5] = Restrict;
Field[5].InField = 2;
Field[5].SurfacesList = {1};
Field[5].CurvesList = {1, 2, 3, 4};
Field[6] = Restrict;
Field[6].InField = 4;
Field[6].SurfacesList = {2};
Field[6].CurvesList = {11, 12, 13, 14};
Field[7] = Min;
Field[7].FieldsList = {5, 6};
Background Field = 7;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;

Physical Surface("upper") = {1};
Physical Surface("lower") = {2};
Physical Curve("upper_top") = {1, 2};
Physical Curve("upper_contact") = {3, 4};
Physical Curve("lower_contact") = {13, 14};
Physical Curve("lower_bottom") = {11, 12};
Physical Point("upper_top_centre") = {1};
Physical Point("upper_contact_point") = {4};
Physical Point("lower_contact_point") = {14};
Physical Point("lower_bottom_centre") = {11};
