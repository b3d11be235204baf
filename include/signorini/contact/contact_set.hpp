// Candidate contact pairs (node, obstacle facet), found by a spatial search over the facets, with their initial
// gaps, and the tributary length of each candidate node on the contact boundary.
#pragma once

#include "signorini/mesh/mesh.hpp"
#include "signorini/obstacles/obstacle.hpp"

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace signorini {

/// Upper bound of -contact_max_it: an active set that needs more iterations is cycling, not converging.
constexpr PetscInt CONTACT_MAX_IT_LIMIT = 10000;
/// The largest -contact_search_radius, in body diagonals: beyond it every facet is paired anyway.
constexpr double SEARCH_RADIUS_MAX = 1e5;

/// Contact options (prefix -contact_), read by ReadContactOptions.
struct ContactOptions {
  std::vector<std::string> groups; ///< -contact_groups: physical groups of candidate nodes (default: whole boundary)
  /// -contact_pairs SLAVE:MASTER,...: facet groups of two bodies in contact (mortar.hpp), slave first
  std::vector<std::pair<std::string, std::string>> pairs;
  std::vector<double> pair_friction; ///< per item of pairs: its MU (-contact_pairs SLAVE:MASTER:MU), -1: none given
  double friction = 0;             ///< -contact_friction: Coulomb's coefficient mu (friction.hpp; 0: frictionless)
  double length = 1;               ///< the body's diagonal (the length scale of the tolerances)
  double search_radius = -1;       ///< -contact_search_radius: pair a node with facets closer than this
  double touch_tol = -1;           ///< -contact_touch_tol: initial gap counted as touching (first active set)
  double gap_tol = -1;             ///< -contact_gap_tol: penetration tolerance of the active-set rule
  double alpha_tol = 1e-8;         ///< -contact_alpha_tol: tolerance on the projection parameter (docs/theory.md §1)
  double c = -1;                   ///< -contact_complementarity_c: weight of the gap in the active-set rule
  double activation_fraction = 0.2; ///< -contact_activation_fraction: activate only penetrations deeper than this
                                    ///< fraction of the deepest one (0: every one, the rule of docs/theory.md §4)
  double activation_gap_factor = -1; ///< -contact_activation_gap_factor: in the first update of a load step, activate
                                     ///< only pairs whose start gap is at most this times the deepest one's (0: off;
                                     ///< default ActivationGapFactor(dim))
  PetscInt max_it = 50;            ///< -contact_max_it: active-set iterations per load step
  PetscBool monitor = PETSC_FALSE;          ///< -contact_monitor
  PetscBool converged_reason = PETSC_FALSE; ///< -contact_converged_reason
};

/// The default of -contact_activation_gap_factor in dimension dim: the ratio of the start gaps at the edge of a smooth
/// contact and where the solve held at its touching point penetrates deepest (the point load's indentation against
/// the parabola: at 1/sqrt(2) of the half-width in 2D, 2; at (4 / 3 pi)^(1/3) of the radius in 3D, (3 pi / 4)^(2/3) =
/// 1.77; docs/solver.md, *First activation*).
double ActivationGapFactor(int dim);

/// Reads and validates the -contact_ options; negative defaults are filled from the mesh's dimension dim (0: not
/// known, -help), the body's size and stiffness (length scale L, stiffness scale k), and the ranges of the tolerances
/// are relative to them (docs/options.md). Collective.
[[nodiscard]] PetscErrorCode ReadContactOptions(MPI_Comm comm, int dim, double L, double k, ContactOptions &opts);

/// The contact inputs that the option readers cannot judge alone, each an error naming the option: in a case without
/// an obstacle, an option that acts only on contact (the pairs, the active-set rule, the kept factorisation of the
/// contact solve), which would be ignored; a -contact_groups group with nodes inside the body, which would make them
/// candidates. Collective.
[[nodiscard]] PetscErrorCode CheckContactInputs(const Mesh &mesh, const Obstacle &obstacle, const ContactOptions &opts);

/// One candidate pair, stored on the rank that owns its node.
struct ContactPair {
  PetscInt vertex;    ///< local vertex
  PetscInt facet;     ///< index into Obstacle::facets
  double n0[3];       ///< normal where the pair was found
  double g0;          ///< gap where the pair was found (docs/theory.md §1: >= 0 open)
  bool inside0;       ///< projects inside the facet where the pair was found
  bool zone0;         ///< the facet is one of the node's own in the reference configuration: X projects onto it,
                      ///< or onto none of the node's facets and this one is the nearest (a node over the wedge of a
                      ///< convex joint); the zone of the linear material
  double x0[3];       ///< position of the node when the pair was found (the reference, or the current position of
                      ///< an svk re-pairing), the start of the path X -> x of the activation rule
};

/// A facet as a node at x sees it: its index, the unit normal and the gap.
struct FacetSide {
  PetscInt facet;
  const double *normal;
  double gap;
};

/// Whether a facet at distance dp (index fp) is nearer to a node than one at distance dq (index fq): by more than
/// 1e-12 length, else the smaller index (the first at a tie, e.g. both meeting at a joint under the node).
inline bool NearerFacet(double dp, PetscInt fp, double dq, PetscInt fq, double length) {
  return dp < dq - 1e-12 * length || (dp <= dq + 1e-12 * length && fp < fq);
}

/// Whether facets a and b, both seen from the node at x, meet at a convex joint of the obstacle (each facet's centre
/// lies behind the other's plane through the node's foot on it): the node is then outside the obstacle when it is
/// outside either of them. False for a facet without a centre (a smooth or unbounded shape) and for coplanar facets.
/// length: the scale of the tolerance (1e-12 of it).
bool ConvexJoint(const Obstacle &obstacle, const FacetSide &a, const FacetSide &b, const double *x, int dim,
                 double length);

/// Sorts pairs by (node in file order, facet), the order every partition agrees on.
void SortPairs(const Mesh &mesh, std::vector<ContactPair> &pairs);

/// Finds the candidate pairs of the owned candidate nodes whose every component is not fixed (fixed[v*dim+k] != 0
/// marks a Dirichlet dof), at the positions X + u_local (u_local: dim values per local vertex; null: the reference
/// configuration). Pairs are sorted by (node in file order, facet) so that every partition finds the same pairs.
/// held (if given): the nodes of the contact groups whose every component is fixed, which are no candidates.
/// Collective.
[[nodiscard]] PetscErrorCode FindContactPairs(const Mesh &mesh, const Obstacle &obstacle, const ContactOptions &opts,
                                              const std::vector<char> &fixed, std::vector<ContactPair> &pairs,
                                              std::vector<char> &candidate, const double *u_local = nullptr,
                                              std::vector<char> *held = nullptr);

/// A candidate node that penetrates the obstacle: how deep, the node in file numbering (from 1; -1 when none) and its
/// reference position.
struct Penetration {
  double depth = 0;
  PetscInt node = -1;
  double x[3] = {0, 0, 0};
};

/// The deepest penetrations of the obstacle, at the positions X + u_local, by owned candidate nodes of facets they
/// have no pair with, the same on every rank: unpaired, of a facet that was farther than the search radius from the
/// node when the pairs were found, or (linear material) whose zone did not hold the node there (found: if given,
/// each such local vertex and facet deeper than the gap tolerance); prescribed, by a node whose motion along the
/// facet's normal the Dirichlet conditions prescribe (fixed: as for FindContactPairs; such a facet gets no pair, the
/// supports hold the node, so the prescribed values put it there), or of a held node (FindContactPairs). Every facet
/// within search radius + max |u| of a node is examined, so none that the node can have reached is missed. At a tie
/// the node with the smallest file number is reported, whatever the partition. reach (if given): max |u| of the
/// examined nodes over all ranks. Collective.
[[nodiscard]] PetscErrorCode DeepestUnpaired(const Mesh &mesh, const Obstacle &obstacle, const ContactOptions &opts,
                                             const std::vector<char> &candidate, const std::vector<char> &held,
                                             const std::vector<char> &fixed,
                                             const std::vector<ContactPair> &pairs, const double *u_local,
                                             Penetration &unpaired, Penetration &prescribed,
                                             std::vector<std::array<PetscInt, 2>> *found = nullptr,
                                             double *reach = nullptr);

/// Tributary length (2D) or area (3D) of every local candidate vertex: the integral of its shape function over each
/// adjacent boundary face whose every vertex is a candidate (half of an edge, a third of a triangle, a quarter of a
/// parallelogram), summed over ranks; with face_thickness (the thickness of each local cell's faces, 2D) also area,
/// the same integrals times the thickness (a node between faces of two thicknesses takes each face's share).
/// Collective.
[[nodiscard]] PetscErrorCode TributaryLengths(const Mesh &mesh, const std::vector<char> &candidate,
                                              std::vector<double> &length,
                                              const std::vector<double> *face_thickness = nullptr,
                                              std::vector<double> *area = nullptr);

} // namespace signorini
