// Which rigid-body motions the supports and a set of active contact constraints leave free: the Gram matrix
// G = sum_r m_r m_r^T of the constraint rows applied to the rigid modes of every body (d translations and d(d-1)/2
// rotations about the body's centre, scaled by its size) is singular exactly when some rigid motion violates no
// constraint. A row against a rigid obstacle acts on its node's body; a mortar row of a pair of bodies
// (MortarCoupling) on both: a body between two others is held only through both interfaces.
#pragma once

#include "signorini/contact/active_set.hpp"
#include "signorini/contact/mortar.hpp"
#include "signorini/mesh/mesh.hpp"

#include <array>
#include <utility>
#include <vector>

namespace signorini {

/// The values of the rigid modes (3 in 2D, 6 in 3D) at x, in direction dir: mode j contributes dir . m_j(x), where
/// m_j(x) is a unit translation or a rotation (x - centre) / size about a coordinate axis. Returns the mode count.
int RigidModeRow(int dim, const double *x, const double *centre, double size, const double *dir, double *row);

/// Smallest eigenvalue of the symmetric n x n matrix a (row major) relative to its largest one (1 when a is zero: no
/// information, treated as singular by the caller through its own count).
double RelativeSmallestEigenvalue(int n, const double *a);

/// A rigid motion of the bodies: the coefficients of each body's modes, body after body.
using RigidMotion = std::vector<double>;

class RigidModes {
public:
  /// Accumulates the Dirichlet rows (fixed[v*dim+k] marks a fixed dof) of the owned vertices, and the rows of every
  /// direction at every owned vertex (the matrix of FreeMotion's fit), per body. mortar (if given): the master terms
  /// of the pairs of bodies. Collective.
  [[nodiscard]] PetscErrorCode Setup(const Mesh &mesh, const std::vector<char> &fixed,
                                     const MortarCoupling *mortar = nullptr);
  /// Whether the Dirichlet rows and the active pairs (normals at their vertices) hold every rigid mode. Collective.
  /// pair_of (if given): per row, the pair whose master terms (mortar) the row has (rows beyond the pairs: friction's
  /// tangential rows); else row p has pair p's.
  [[nodiscard]] PetscErrorCode Held(const std::vector<PairKey> &keys, const std::vector<std::array<double, 3>> &normals,
                                    const std::vector<char> &active, bool &held,
                                    const std::vector<std::size_t> *pair_of = nullptr) const;
  /// The rigid motion nearest to the displacement du (local vertex layout, du[v*dim+k]; least squares over the owned
  /// vertices) among those the Dirichlet rows and the active pairs leave free: its mode coefficients a (zero when
  /// every mode is held). pair_of: as Held's. Collective.
  [[nodiscard]] PetscErrorCode FreeMotion(const std::vector<PairKey> &keys,
                                          const std::vector<std::array<double, 3>> &normals,
                                          const std::vector<char> &active, const double *du, RigidMotion &a,
                                          const std::vector<std::size_t> *pair_of = nullptr) const;
  /// The part of the load f (dim values per local vertex, the owned ones counted) along the rigid motions that the
  /// Dirichlet rows leave free which no non-negative forces of the pairs (along their normals, less their master
  /// terms' for a pair of bodies) balance: min over lambda >= 0 of |Z^T (F + A lambda)| / |Z^T F|, F the load's and A
  /// the pairs' generalised forces on the modes, Z an orthonormal basis of the free modes (NonNegativeLeastSquares).
  /// 0 when the supports hold every mode or the load has no part along the free ones. Collective.
  [[nodiscard]] PetscErrorCode Unbalanced(const std::vector<PairKey> &keys,
                                          const std::vector<std::array<double, 3>> &normals, const double *f,
                                          double &unbalanced) const;
  /// The rate at which the gap of pair p changes along the rigid motion a (its row of B applied to the motion,
  /// with the sign of the gap).
  double PairRate(std::size_t p, const std::vector<PairKey> &keys, const std::vector<std::array<double, 3>> &normals,
                  const RigidMotion &a) const;
  /// The displacement v (dim values) of local vertex vertex under the rigid motion a.
  void Motion(PetscInt vertex, const RigidMotion &a, double *v) const;
  /// The size of a rigid motion: the norm of its coefficients (a rotation's is the displacement it gives at the
  /// body's size from its centre).
  double Magnitude(const RigidMotion &a) const;

private:
  /// The row of pair p on the modes, as (mode, value) entries: its node's body's modes along its normal, less the
  /// master terms' (mortar).
  void PairRow(std::size_t p, const std::vector<PairKey> &keys, const std::vector<std::array<double, 3>> &normals,
               std::vector<std::pair<int, double>> &row, std::size_t terms_of) const;
  void PairRow(std::size_t p, const std::vector<PairKey> &keys, const std::vector<std::array<double, 3>> &normals,
               std::vector<std::pair<int, double>> &row) const {
    PairRow(p, keys, normals, row, p);
  }
  /// Adds the outer product of a sparse row to the n_ x n_ matrix g.
  void AddRow(const std::vector<std::pair<int, double>> &row, std::vector<double> &g) const;
  /// Appends the modes of body b at x in direction dir, times scale, to row.
  void AppendModes(PetscInt b, const double *x, const double *dir, double scale,
                   std::vector<std::pair<int, double>> &row) const;
  /// The free modes of a Gram matrix (n_ x n_): the indices of its eigenvectors (vec, n_ x n_ row major, column j the
  /// j-th) whose eigenvalues are at most FREE_MODE of the largest.
  std::vector<int> FreeModes(const std::vector<double> &gram, std::vector<double> &vec) const;
  /// out[i] = sum over the owned vertices of field(v) . m_i(v) (field: dim values per local vertex), summed over the
  /// ranks: a displacement's or a load's projection on the modes. Collective.
  [[nodiscard]] PetscErrorCode OnModes(const double *field, std::vector<double> &out) const;
  /// The Gram matrix of the Dirichlet rows and the active pairs' rows (n_ x n_). Collective.
  [[nodiscard]] PetscErrorCode Gram(const std::vector<PairKey> &keys, const std::vector<std::array<double, 3>> &normals,
                                    const std::vector<char> &active, std::vector<double> &gram,
                                    const std::vector<std::size_t> *pair_of = nullptr) const;

  const Mesh *mesh_ = nullptr;
  const MortarCoupling *mortar_ = nullptr;
  int per_body_ = 3, n_ = 3; ///< modes per body, modes in all
  std::vector<double> centre_, size_; ///< per body: its centre (3 values) and size
  std::vector<double> g_dirichlet_;
  std::vector<double> m_vertices_; ///< sum over the vertices of the rows of every direction (the fit's matrix)
};

} // namespace signorini
