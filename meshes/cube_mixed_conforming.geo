// A box [0, 2] x [0, 1] x [0, 1] meshed conformingly in two halves that share the face x = 1: graded hexahedra on
// x in [0, 1] (those of cube.geo at -mesh_size_factor 1: transfinite, recombined) and tetrahedra on x in [1, 2]. The
// tetrahedral half is the (unstructured) extrusion of the hexahedra's quadrilateral face x = 1, so gmsh joins its
// tetrahedra to those quadrilaterals with pyramids, one per quadrilateral: a conforming mesh of all three cell types.
// -mesh_size_factor (gmsh -clscale) refines both halves: the hexahedra's divisions and the tetrahedra's size.
// Physical groups: body (volume); bottom (z = 0), top (z = 1), left (x = 0), right (x = 2), front (y = 0),
// back (y = 1) (surfaces); origin (the point (0, 0, 0)).
L = 1;
f = Mesh.MeshSizeFactor;
n = Round(5 / f); layers = Round(4 / f);
Mesh.MeshSizeMax = 0.2; // gmsh scales it by the size factor
Point(1) = {0, 0, 0}; Point(2) = {L, 0, 0}; Point(3) = {L, L, 0}; Point(4) = {0, L, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {4, 3}; Line(4) = {1, 4};
Curve Loop(1) = {1, 2, -3, -4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = n + 1 Using Progression 1.3 ^ (5 / n);
Transfinite Surface{1};
Recombine Surface{1};
hex[] = Extrude {0, 0, L} { Surface{1}; Layers{layers}; Recombine; };
tet[] = Extrude {L, 0, 0} { Surface{hex[3]}; };
e = 1e-6;
Physical Volume("body") = {hex[1], tet[1]};
Physical Surface("bottom") = Surface In BoundingBox{-e, -e, -e, 2 * L + e, L + e, e};
Physical Surface("top") = Surface In BoundingBox{-e, -e, L - e, 2 * L + e, L + e, L + e};
Physical Surface("left") = Surface In BoundingBox{-e, -e, -e, e, L + e, L + e};
Physical Surface("right") = Surface In BoundingBox{2 * L - e, -e, -e, 2 * L + e, L + e, L + e};
Physical Surface("front") = Surface In BoundingBox{-e, -e, -e, 2 * L + e, e, L + e};
Physical Surface("back") = Surface In BoundingBox{-e, L - e, -e, 2 * L + e, L + e, L + e};
Physical Point("origin") = {1};
