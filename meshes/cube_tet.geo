// Unit cube of tetrahedra for the 3D rigid-plane case, finer towards the corner (1, 1, 0) so that the tributary
// areas of the bottom nodes differ. cube.geo is the same cube in hexahedra.
// Physical groups: body (volume), bottom (z = 0), top (z = 1), left (x = 0), front (y = 0) (surfaces).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
MeshSize{PointsOf{Volume{1};}} = 0.3;
MeshSize{Point{3}} = 0.12;
Mesh.Algorithm3D = 1;
Physical Volume("body") = {1};
Physical Surface("left") = {1};
Physical Surface("front") = {3};
Physical Surface("bottom") = {5};
Physical Surface("top") = {6};
