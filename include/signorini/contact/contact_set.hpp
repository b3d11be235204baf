// Candidate contact pairs (node, obstacle facet), found by a spatial search over the facets, with their initial
// gaps, and the tributary length of each candidate node on the contact boundary.
#pragma once

#include "signorini/mesh/mesh.hpp"
#include "signorini/obstacles/obstacle.hpp"

#include <string>
#include <vector>

namespace signorini {

/// Upper bound of -contact_max_it: an active set that needs more iterations is cycling, not converging.
constexpr PetscInt CONTACT_MAX_IT_LIMIT = 10000;

/// Contact options (prefix -contact_), read by ReadContactOptions.
struct ContactOptions {
  std::vector<std::string> groups; ///< -contact_groups: physical groups of candidate nodes (default: whole boundary)
  double search_radius = -1;       ///< -contact_search_radius: pair a node with facets closer than this
  double touch_tol = -1;           ///< -contact_touch_tol: initial gap counted as touching (first active set)
  double gap_tol = -1;             ///< -contact_gap_tol: penetration tolerance of the active-set rule
  double alpha_tol = 1e-8;         ///< -contact_alpha_tol: tolerance on the projection parameter (seed Eq. 27)
  double c = -1;                   ///< -contact_complementarity_c: weight of the gap in the active-set rule
  double activation_fraction = 0.9; ///< -contact_activation_fraction: activate only penetrations deeper than this
                                    ///< fraction of the deepest one (0: every penetration, the seed's rule)
  PetscInt max_it = 50;            ///< -contact_max_it: active-set iterations per load step
  PetscBool monitor = PETSC_FALSE;          ///< -contact_monitor
  PetscBool converged_reason = PETSC_FALSE; ///< -contact_converged_reason
};

/// Reads and validates the -contact_ options; negative defaults are filled from the body's size and stiffness
/// (length scale L, stiffness scale k), and the ranges of the tolerances are relative to them (README). Collective.
[[nodiscard]] PetscErrorCode ReadContactOptions(MPI_Comm comm, double L, double k, ContactOptions &opts);

/// One candidate pair, stored on the rank that owns its node.
struct ContactPair {
  PetscInt vertex;    ///< local vertex
  PetscInt facet;     ///< index into Obstacle::facets
  double n0[3];       ///< normal at the reference position
  double g0;          ///< initial gap (Eq. 8 with the sign of ARCHITECTURE.md: >= 0 open)
  bool inside0;       ///< projects inside the facet initially
};

/// Finds the candidate pairs of the owned candidate nodes whose every component is not fixed (fixed[v*dim+k] != 0
/// marks a Dirichlet dof). Pairs are sorted by (node in file order, facet) so that every partition finds the same
/// pairs. Collective.
[[nodiscard]] PetscErrorCode FindContactPairs(const Mesh &mesh, const Obstacle &obstacle, const ContactOptions &opts,
                                              const std::vector<char> &fixed, std::vector<ContactPair> &pairs,
                                              std::vector<char> &candidate);

/// Tributary length of every local candidate vertex: half of each adjacent boundary edge whose both ends are
/// candidates (summed over ranks). Collective.
[[nodiscard]] PetscErrorCode TributaryLengths(const Mesh &mesh, const std::vector<char> &candidate,
                                              std::vector<double> &length);

} // namespace signorini
