// Cattaneo-Mindlin partial slip (2D, plane strain): two equal half-cylinders of radius R = 8, mirror images of each
// other about y = 0, touching at the origin: the upper one (centre (0, R)) above, the lower one (centre (0, -R)) below,
// each with a flat side (the upper's top at y = R, the lower's bottom at y = -R). Equal bodies of one material pressed
// by mirror-symmetric supports have no relative tangential displacement on their interface, as Johnson's half-spaces
// (Contact Mechanics, 7.1), so a tangential force afterwards finds no locked-in traction. The upper edge is the slave
// side (finer); scale every size with -mesh_size_factor (or gmsh -clscale).
// Physical groups: upper, lower (surfaces); upper_top, upper_contact, lower_contact, lower_bottom (curves).
R = 8;
h_far = 0.8;
h_slave = 0.01;
h_master = 0.015;
Point(1) = {0, R, 0, h_far}; Point(2) = {-R, R, 0, h_far}; Point(3) = {R, R, 0, h_far};
Point(4) = {0, 0, 0, h_slave};
Line(1) = {2, 1}; Line(2) = {1, 3};
Circle(3) = {3, 1, 4}; Circle(4) = {4, 1, 2};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Point(11) = {0, -R, 0, h_far}; Point(12) = {R, -R, 0, h_far}; Point(13) = {-R, -R, 0, h_far};
Point(14) = {0, 0, 0, h_master};
Line(11) = {13, 11}; Line(12) = {11, 12};
Circle(13) = {12, 11, 14}; Circle(14) = {14, 11, 13};
Curve Loop(2) = {-14, -13, -12, -11}; Plane Surface(2) = {2};

// Fine near the contact (within 1.2 of it, where the contact half-width is about 0.72), coarse from 5 away.
Field[1] = Distance;
Field[1].PointsList = {4};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h_slave;
Field[2].SizeMax = h_far;
Field[2].DistMin = 1.2;
Field[2].DistMax = 5.0;
Field[3] = Distance;
Field[3].PointsList = {14};
Field[4] = Threshold;
Field[4].InField = 3;
Field[4].SizeMin = h_master;
Field[4].SizeMax = h_far;
Field[4].DistMin = 1.2;
Field[4].DistMax = 5.0;
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
