// Lame thick-walled cylinder (inner radius 1, outer radius 2), quarter model, quadrilaterals: lame.geo recombined
// (Blossom). Physical groups as in lame.geo. Refine with -mesh_size_factor (or gmsh -clscale).
// Note: gmsh 4.8's Frontal-Delaunay for quads (Mesh.Algorithm = 8) crashes on this geometry; keep the default.
Include "lame.geo";
Mesh.RecombinationAlgorithm = 1;
Recombine Surface{1};
