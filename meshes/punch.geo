// A rigid punch with a spherical end for options/punch_on_plate.yml, as a meshed obstacle (-obstacle_mesh): the
// quarter (x, y >= 0) of the sphere of radius 1 centred at (0, 0, 1.252) below z = 0.452, whose lowest point lies
// 0.002 above the plate's top (z = 0.25), meshed with triangles of size about 0.03. Physical surface "tip" (the
// spherical face, listed first among the boundary surfaces of the intersection); its triangles' right-hand normals
// point out of the sphere, into the plate below.
SetFactory("OpenCASCADE");
R = 1; zc = 0.25 + 0.002 + R;
Sphere(1) = {0, 0, zc, R};
Box(2) = {0, 0, zc - R, 0.7, 0.7, 0.2};
v[] = BooleanIntersection{ Volume{1}; Delete; }{ Volume{2}; Delete; };
s[] = Boundary{ Volume{v[0]}; };
Delete { Volume{v[0]}; } // the surfaces stay: only they are meshed (-obstacle_mesh punch.geo:tip meshes no volume)
Mesh.MeshSizeMax = 0.03;
Physical Surface("tip") = {s[0]};
