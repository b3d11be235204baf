// Lame thick spherical shell of lame3d.geo in hexahedra: gmsh splits each tetrahedron into four hexahedra
// (Mesh.SubdivisionAlgorithm = 2), an unstructured all-hexahedral mesh of the curved octant with the same physical
// groups. Refine with -mesh_size_factor (or gmsh -clscale); the hexahedra are about half the size of lame3d.geo's
// tetrahedra at the same factor.
Include "lame3d.geo";
Mesh.SubdivisionAlgorithm = 2;
