// The mesh's parallel file (-mesh_save, a .h5 -mesh_file): PETSc's DMPlex HDF5 format with signorini's own data.
#pragma once

#include <petscsys.h>

#include <string>

namespace signorini {

/// What a file written by -mesh_save holds, besides PETSc's DMPlex HDF5 groups of the DMPlex named MESH_H5_DM
/// (topology, coordinates, labels "phys_<group>" and the boundary's):
///   - the section and vector "point_data" on the DM MESH_H5_POINT_DM: each vertex its index in the gmsh file, each
///     cell its index in the file, its vertex count, its vertices in gmsh's order (file indices), its face codes;
///   - group MESH_H5_GROUP: attributes "format" (MESH_H5_FORMAT), "dim", "nodes", "cells", "groups" (the physical
///     groups, "count\n" then "<dim><name>\n" each), and the vectors "node_tags", "cell_tags" (the file's tags in
///     the file's order).
inline const char *const MESH_H5_DM = "signorini_mesh";
inline const char *const MESH_H5_POINT_DM = "signorini_point_data";
inline const char *const MESH_H5_GROUP = "/signorini";
inline const char *const MESH_H5_FORMAT = "signorini mesh 1";

/// The name a -mesh_save file is written under before it is renamed to path: next to it, hidden, with the process
/// id. Local.
std::string MeshSaveTemporaryName(const std::string &path);

/// Checks on rank 0 that -mesh_save path can be written (a file can be made next to it, it is no directory); an
/// error names -mesh_save, path and what was expected on every rank. Leaves nothing behind. Collective.
[[nodiscard]] PetscErrorCode CheckMeshSavePath(MPI_Comm comm, const std::string &path);

/// "" when the file at path starts with HDF5's signature, else the reason it is no HDF5 file. Local.
std::string CheckHdf5Signature(const std::string &path);

} // namespace signorini
