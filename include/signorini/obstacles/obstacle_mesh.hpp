// Meshed rigid obstacles (-obstacle_mesh FILE[:GROUP]): the elements of a gmsh file as oriented facets, segments of
// a polyline in 2D, triangles in 3D, after checking that they form a consistently oriented manifold.
#pragma once

#include "signorini/mesh/serial_mesh.hpp"
#include "signorini/obstacles/obstacle.hpp"

#include <memory>
#include <string>
#include <vector>

namespace signorini {

/// Checks the elements of an obstacle mesh for a body of dimension dim and, when they pass, appends their facets to
/// out. dim 2: 2-node lines become Segments P0 -> P1 (normal: the left normal); every node is shared by at most two
/// lines, which chain head to tail, and all nodes lie in one plane z = const. dim 3: triangles become Triangles and
/// quadrilaterals two Triangles (normal: right-hand rule of the node order); every edge is shared by at most two
/// facets, which traverse it in opposite directions. No element may have zero length or area. Returns "" or the
/// first error, naming the file (name) and the element's tag. Not collective.
std::string BuildMeshFacets(const ElementSet &set, int dim, const std::string &name,
                            std::vector<std::unique_ptr<Facet>> &out);

/// Reads every -obstacle_mesh file of obstacle (found by ReadObstacle) on rank 0, for a body of dimension dim, checks
/// it (BuildMeshFacets) and appends its facets to obstacle.facets on every rank. An error is raised on every rank.
/// Collective.
[[nodiscard]] PetscErrorCode LoadObstacleMeshes(MPI_Comm comm, int dim, Obstacle &obstacle);

} // namespace signorini
