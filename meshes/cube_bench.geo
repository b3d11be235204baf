// Unit cube of n^3 hexahedra for the 3D benchmark family `cube` (scripts/benchmark.py) and options/cube_under_sphere.yml:
// n = 16 / the mesh size factor (-mesh_size_factor F, gmsh's -clscale F): F = 0.5 gives 32^3 cells (108k dofs),
// 0.25 gives 64^3 (824k), 0.16 gives 100^3 (3.06M), 0.125 gives 128^3 (6.4M).
// Physical groups: body (volume), bottom (z = 0), top (z = 1), xmin, xmax, ymin, ymax (surfaces).
n = Round(16 / Mesh.MeshSizeFactor);
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {4, 3}; Line(4) = {1, 4};
Curve Loop(1) = {1, 2, -3, -4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = n + 1;
Transfinite Surface{1};
Recombine Surface{1};
out[] = Extrude {0, 0, 1} { Surface{1}; Layers{n}; Recombine; };
Physical Volume("body") = {out[1]};
Physical Surface("bottom") = {1};
Physical Surface("top") = {out[0]};
Physical Surface("ymin") = {out[2]};
Physical Surface("xmax") = {out[3]};
Physical Surface("ymax") = {out[4]};
Physical Surface("xmin") = {out[5]};
