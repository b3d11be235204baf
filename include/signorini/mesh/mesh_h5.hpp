// The mesh's parallel file (-mesh_save, a .h5 -mesh_file): PETSc's DMPlex HDF5 format with signorini's own blocks,
// which every rank reads its part of.
#pragma once

#include <petscsys.h>

#include <string>

namespace signorini {

/// What a file written by -mesh_save holds: PETSc's DMPlex HDF5 groups of the DMPlex named MESH_H5_DM (topology,
/// coordinates, labels "phys_<group>" and the boundary's), which PETSc's DMLoad reads, and in group MESH_H5_GROUP
/// what signorini reads back, every rank its block (PETSc 3.18 loads the DMPlex's topology on rank 0):
///   - attributes "format" (MESH_H5_FORMAT), "dim", "nodes", "cells" (the gmsh file's counts), "vertices" (the
///     DMPlex's), "groups" (the physical groups, "count\n" then "<dim><name>\n" each);
///   - per cell, in the DMPlex's order (the writing ranks' cells in rank order): "cell_sizes" (its vertex count),
///     "cell_vertices" (its vertices in gmsh's order, numbered as the vertex datasets are), "cell_orig" (its index in
///     the gmsh file), "cell_face_sizes" and "cell_faces" (the face codes of its group and boundary faces),
///     "cell_label_sizes" and "cell_labels" (the labels that hold it: a group's index, the groups' count for the
///     boundary);
///   - per vertex, the writing ranks' owned vertices in rank order: "vertex_orig" (its index in the gmsh file),
///     "vertex_coordinates" (vertices x dim), "vertex_label_sizes" and "vertex_labels";
///   - "node_tags", "cell_tags": the gmsh file's tags in the file's order.
/// A dataset that would be empty on every rank is not written. All values are stored as doubles (PETSc vectors).
inline const char *const MESH_H5_DM = "signorini_mesh";
inline const char *const MESH_H5_GROUP = "/signorini";
inline const char *const MESH_H5_FORMAT = "signorini mesh 2";

/// The name a -mesh_save file is written under before it is renamed to path: next to it, hidden, with the process
/// id. Local.
std::string MeshSaveTemporaryName(const std::string &path);

/// Checks on rank 0 that -mesh_save path can be written (a file can be made next to it, it is no directory); an
/// error names -mesh_save, path and what was expected on every rank. Leaves nothing behind. Collective.
[[nodiscard]] PetscErrorCode CheckMeshSavePath(MPI_Comm comm, const std::string &path);

/// "" when the file at path starts with HDF5's signature, else the reason it is no HDF5 file. Local.
std::string CheckHdf5Signature(const std::string &path);

} // namespace signorini
