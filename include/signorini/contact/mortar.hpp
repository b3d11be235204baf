// Contact between two deformable bodies (-contact_pairs SLAVE:MASTER): one constraint row per slave node with the
// dual mortar basis (Wohlmuth 2000; Popp, Gee, Wall 2009), so that the slave block D is diagonal and the rows stay
// node-based as for a rigid obstacle. The weighted gap of slave node j, divided by D_jj, is
//   g_j = n_j . (x_j - sum_l w_jl x_l),   w_jl = M_jl / D_jj,
// with n_j the interface's nodal normal pointing from the master into the slave body (the two surfaces' normals
// weighted by the bodies' compliances, mortar.cpp's InterfaceNormal: the master's for a rigid master), D_jj = int psi_j N_j and
// M_jl = int psi_j N_l^master over the slave facets' overlap with the master facets (segment-based integration:
// each slave facet is cut where the master facets' projections along its normal begin and end, and each piece is
// integrated exactly by Gauss points). The dual basis psi is built on each slave facet's overlap (biorthogonal to
// the slave shape functions there), so a facet that the master covers only in part keeps D diagonal and positive.
// With this scaling the multiplier is the normal force on the slave node and pressure = lambda / tributary length,
// as for a rigid obstacle, and the master carries - w_jl lambda_j n_j. Linear material: the integrals and normals of
// the reference configuration, fixed through the run; svk: those of the current configuration, computed again at
// every iterate (Update), and by default their variation enters the Newton tangent (UseConsistentTangent, Linearise:
// docs/theory.md §8).
#pragma once

#include "signorini/contact/active_set.hpp"
#include "signorini/contact/constraints.hpp"
#include "signorini/contact/contact_set.hpp"
#include "signorini/core/handle.hpp"
#include "signorini/fem/dof_map.hpp"

#include <array>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

namespace signorini {

/// The mortar rows of the -contact_pairs interfaces and their master terms. A mortar pair is a ContactPair whose
/// facet is FacetBase() + the interface's index: its slave part (n_j on the slave node, the gap g0 + n_j . u_j) is
/// evaluated as a rigid obstacle's pair is, and this object adds the master part (Bind, ExtendRows, AddMasterGaps,
/// AddMasterForces) through a matrix G of the master terms (rows: the owned pairs; columns: the displacement rows).
class MortarCoupling {
public:
  /// Computes the rows of the owned slave nodes of every interface in the reference configuration (u_local null:
  /// the interfaces are checked, CheckInterface), or in the configuration of the displacement u_local (dim values per
  /// local vertex); facet_base: the obstacle's facet count. fixed marks the Dirichlet dofs per local vertex dof.
  /// Collective.
  [[nodiscard]] PetscErrorCode Build(const Mesh &mesh, const ContactOptions &opts, const std::vector<char> &fixed,
                                     PetscInt facet_base, const double *u_local = nullptr);
  /// The compliance (1 - nu^2) / (E t) (plane stress: 1 / (E t); t the thickness in 2D) of every body, before Build: the rows' normals weight the two
  /// surfaces' by it (mortar.cpp, InterfaceNormal). Without it the master's normal alone.
  void SetCompliance(std::vector<double> compliance) { compliance_ = std::move(compliance); }
  /// svk (before Build): the rows keep what their consistent tangent needs (Linearise): the slave facets around each
  /// slave node and the master facets they overlap, and each row gets the columns of its neighbouring slave nodes
  /// (ExtendRows, coefficient 0), so that the displacement block's pattern holds the tangent's entries.
  void UseConsistentTangent() { tangent_ = true; }
  bool ConsistentTangent() const { return tangent_; }
  /// svk: the rows again in the configuration of u_local; changed: the pairs or the master nodes of a row changed
  /// (the system's pattern with them), on any rank. Collective.
  [[nodiscard]] PetscErrorCode Update(const Mesh &mesh, const ContactOptions &opts, const std::vector<char> &fixed,
                                      const double *u_local, bool &changed);
  /// Gives the mortar pairs among pairs their rows' current normals and gaps g0.
  void RefreshPairs(std::vector<ContactPair> &pairs) const;
  bool Empty() const { return interfaces_ == 0; }
  PetscInt Interfaces() const { return interfaces_; }
  PetscInt FacetBase() const { return facet_base_; }
  bool IsMortar(const ContactPair &p) const { return p.facet >= facet_base_; }
  /// Per local vertex: a node of a master group.
  const std::vector<char> &MasterVertices() const { return master_vertex_; }
  /// Appends the mortar pairs (unsorted) and marks the slave nodes as candidates.
  void AppendPairs(const Mesh &mesh, std::vector<ContactPair> &pairs, std::vector<char> &candidate) const;
  /// For the current numbering: the master nodes' global rows and G. Collective.
  [[nodiscard]] PetscErrorCode Bind(const Mesh &mesh, const DofMap &dofs, const std::vector<char> &fixed,
                                    const std::vector<ContactPair> &pairs);
  /// Appends the master nodes' free columns (coefficient w_jl n_j, the row of B being -grad g) to the mortar rows.
  void ExtendRows(std::vector<ConstraintRow> &rows) const;
  /// Adds the master part of the gap, - n_j . sum_l w_jl u_l, at the displacement u_local (dim values per local
  /// vertex, prescribed values included). Collective.
  [[nodiscard]] PetscErrorCode AddMasterGaps(const Mesh &mesh, const DofMap &dofs, const double *u_local,
                                             std::vector<PairState> &states) const;
  /// The forces of the multipliers lambda on the master nodes (G^T lambda over the owned displacement rows, every
  /// component) into master, and their sums per component over this rank's nodes added to sum (dim values).
  /// Collective.
  [[nodiscard]] PetscErrorCode MasterForces(const Mesh &mesh, const DofMap &dofs, const std::vector<double> &lambda,
                                            std::vector<double> &master, double *sum) const;
  /// out[i] += sign (G^T lambda)_i over the owned displacement rows (local offsets, every component): the forces of
  /// the multipliers on the master nodes, - w_jl lambda_j n_j. Collective.
  [[nodiscard]] PetscErrorCode AddMasterForces(const std::vector<double> &lambda, double sign,
                                               std::vector<double> &out) const;

  /// The consistent Newton tangent of the mortar rows at the configuration of the last Update (UseConsistentTangent):
  /// the rows' coefficients c_j (-n_j on the slave node j, w_jl n_j on its master nodes l) and weighted gaps g_j
  /// depend on the slave and master nodes around j through n_j and w_jl. For every owned pair p with a row that is
  /// active or carries a multiplier, by central differences of the row's own integrals over its local facets: adds
  /// lambda_p dc_p/du (the variation of the contact forces B^T lambda) to K (rows and columns: the free dofs of the
  /// row's pattern; block: K is the displacement block of a nested matrix, numbered by DofMap::UBlockRow), and on an
  /// active pair replaces rows[p]'s coefficients by -dg_p/du (the linearised gap), its frozen coefficients given back
  /// in columns[p] (the column of B^T: the residual's forces keep them). Collective (K's off-rank entries).
  [[nodiscard]] PetscErrorCode Linearise(const Mesh &mesh, const DofMap &dofs, const std::vector<char> &fixed,
                                         const std::vector<double> &lambda, const std::vector<char> &active, Mat K,
                                         bool block, std::vector<ConstraintRow> &rows,
                                         std::vector<std::vector<double>> &columns) const;

  /// A facet of a slave or master group as every rank sees it after the gather: its nodes (file numbering), bodies,
  /// and current and reference positions.
  struct Facet {
    int n = 0;
    std::array<PetscInt, 4> node{}, body{};
    std::array<std::array<double, 3>, 4> x{}, X{};
  };

  /// Bind builds the weights' matrix W too (MasterDisplacements, AddMasterVectorForces: friction between bodies).
  void KeepWeights() { weights_ = true; }
  /// Appends to row the free master columns of pair p in ExtendRows' order, with coefficients scale w_jl dir_k (the
  /// master part of a row along the direction dir: friction's tangential rows).
  void MasterColumns(std::size_t p, const double *dir, double scale, SparseRow &row) const;
  /// The weighted master displacement of every pair, m_p = sum_l w_jl u_l (dim values per pair; 0 for an obstacle's
  /// pair), at u_local (dim values per local vertex); needs KeepWeights. Collective.
  [[nodiscard]] PetscErrorCode MasterDisplacements(const Mesh &mesh, const DofMap &dofs, const double *u_local,
                                                   std::vector<double> &m) const;
  /// out[i] += sign times the forces on the master nodes of the forces F (dim values per pair) on the slave nodes,
  /// - w_jl F_p, over the owned displacement rows (local offsets). Collective.
  [[nodiscard]] PetscErrorCode AddMasterVectorForces(const std::vector<double> &F, double sign, double *out,
                                                     PetscInt n) const;

  /// A master node of a row: its file number (from 0), its weight w_jl = M_jl / D_jj, its position and its body.
  struct MasterTerm {
    PetscInt node;
    double w;
    double x[3];
    PetscInt body;
  };
  /// The master terms of pair p (Bind's numbering of the pairs); null for an obstacle's pair.
  const std::vector<MasterTerm> *Terms(std::size_t p) const;

private:
  struct Row {
    PetscInt vertex, facet; ///< the slave node (local vertex) and the pair's facet index
    double n[3], g0, D;
    std::vector<MasterTerm> terms;
    /// UseConsistentTangent: the slave facets that hold the slave node and the master facets that they overlap (the
    /// row's integrals), and the other nodes of those slave facets.
    std::vector<Facet> near_slave, near_master;
    std::vector<std::vector<int>> near_hits; ///< per slave facet of near_slave, its master facets in near_master
    std::vector<PetscInt> neighbours;
  };
  /// The most that two bodies may overlap at the start, in body diagonals (a faceted curved interface overlaps by
  /// about h^2 / R; more is a wrong mesh).
  static constexpr double START_OVERLAP = 1e-3;
  /// Refuses an interface (rows from first on) that no row constrains, or whose bodies start inside each other by
  /// more than START_OVERLAP, naming the deepest slave node. Collective.
  [[nodiscard]] PetscErrorCode CheckInterface(const Mesh &mesh, const ContactOptions &opts, PetscInt item,
                                              std::size_t first) const;
  /// The rows of one interface's owned slave nodes (2D: segments). Collective.
  [[nodiscard]] PetscErrorCode BuildInterface(const Mesh &mesh, const ContactOptions &opts,
                                              const std::vector<char> &fixed, PetscInt item, const double *u_local);

  /// y = M x with x the displacement u_local (dim values per local vertex) in the system's layout. Collective.
  [[nodiscard]] PetscErrorCode Apply(Mat M, const Mesh &mesh, const DofMap &dofs, const double *u_local, Vec x,
                                     Vec y) const;

  PetscInt interfaces_ = 0, facet_base_ = 0;
  std::vector<double> compliance_; ///< per body (SetCompliance)
  bool weights_ = false;           ///< KeepWeights
  bool tangent_ = false;           ///< UseConsistentTangent
  double radius_ = 0;              ///< the search radius of the last Build
  std::vector<Row> rows_;
  std::vector<char> slave_, master_vertex_; ///< local vertices of a slave group, of a master group
  /// Bind: per pair the index of its row in rows_ (-1: an obstacle's pair); per master node its first global row and
  /// its fixed components (bit k).
  std::vector<PetscInt> pair_row_;
  std::unordered_map<PetscInt, std::pair<PetscInt, int>> master_;
  /// Bind: per pair its master nodes' free columns in the system and their coefficients w_jl n_j (ExtendRows).
  std::vector<std::vector<std::pair<PetscInt, double>>> free_columns_;
  /// Bind, UseConsistentTangent: per pair its neighbouring slave nodes' free columns (ExtendRows, coefficient 0).
  std::vector<std::vector<PetscInt>> neighbour_columns_;
  /// Bind: per pair its free master columns' weights w_jl and components, in free_columns_' order.
  struct FreeTerm {
    double w;
    int k;
  };
  std::vector<std::vector<FreeTerm>> free_terms_;
  /// Bind: W, the weights w_jl per pair and component (rows: dim per owned pair; columns as G's), and its vectors.
  MatH W_;
  mutable VecH wx_, wy_;
  PetscInt dim_ = 2;
  MatH G_;
  mutable VecH x_, y_; ///< work vectors of G's columns and rows
};

} // namespace signorini
