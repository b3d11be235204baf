// Contact patch test (3D): two unit cubes stacked with a flat interface at z = 1 and non-matching meshes on its two
// sides (3 cells across below, 5 above for hexahedra; mesh sizes 1/3 and 1/4.3 for tetrahedra). Each box has its own
// faces and nodes on the interface (no boolean fragments), so the two bodies share no nodes.
// -setnumber lower_hex 1 / upper_hex 1: hexahedra in that block (transfinite, recombined); 0: tetrahedra.
// Physical groups: lower, upper (volumes); bottom, lower_top, upper_bottom, top, x0 (both blocks' faces at x = 0),
// y0 (at y = 0) (surfaces).
SetFactory("OpenCASCADE");
DefineConstant[lower_hex = 1, upper_hex = 1];
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {0, 0, 1, 1, 1, 1};
// The faces of an OpenCASCADE box are numbered x = min, x = max, y = min, y = max, z = min, z = max.
MeshSize{PointsOf{Volume{1};}} = 1 / 3;
MeshSize{PointsOf{Volume{2};}} = 1 / 4.3;
If (lower_hex)
  Transfinite Curve{Unique(Abs(Boundary{Boundary{Volume{1};}}))} = 4;
  Transfinite Surface{1:6};
  Recombine Surface{1:6};
  Transfinite Volume{1};
EndIf
If (upper_hex)
  Transfinite Curve{Unique(Abs(Boundary{Boundary{Volume{2};}}))} = 6;
  Transfinite Surface{7:12};
  Recombine Surface{7:12};
  Transfinite Volume{2};
EndIf
Physical Volume("lower") = {1};
Physical Volume("upper") = {2};
Physical Surface("bottom") = {5};
Physical Surface("lower_top") = {6};
Physical Surface("upper_bottom") = {11};
Physical Surface("top") = {12};
Physical Surface("x0") = {1, 7};
Physical Surface("y0") = {3, 9};
