// Benchmark beam (scripts/benchmark.py): the cantilever of beam.geo, 10 x 1, structured quadrilaterals, same physical
// groups (body, left, top, bottom, right, tip), refined by the mesh size factor F (-mesh_size_factor F, gmsh -clscale F):
// element size h = 0.25 F, so F = 1 gives beam.geo's 41 x 5 nodes and the displacement dofs are about 2 (40/F + 1)(4/F + 1).
L = 10; H = 1; h = 0.25;
f = Mesh.MeshSizeFactor;
nx = Round(L / (h * f)) + 1;
ny = Round(H / (h * f)) + 1;
Point(1) = {0, 0, 0, h}; Point(2) = {L, 0, 0, h}; Point(3) = {L, H, 0, h}; Point(4) = {0, H, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = nx;
Transfinite Curve{2, 4} = ny;
Transfinite Surface{1};
Recombine Surface{1};
Physical Surface("body") = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Point("tip") = {2};
