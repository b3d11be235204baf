// Which rigid-body motions the supports and a set of active contact constraints leave free: the Gram matrix
// G = sum_r m_r m_r^T of the constraint rows applied to the rigid modes (d translations and d(d-1)/2 rotations
// about the body's centre, scaled by its size) is singular exactly when some rigid motion violates no constraint.
#pragma once

#include "signorini/contact/active_set.hpp"
#include "signorini/mesh/mesh.hpp"

#include <array>
#include <vector>

namespace signorini {

/// The values of the rigid modes (3 in 2D, 6 in 3D) at x, in direction dir: mode j contributes dir . m_j(x), where
/// m_j(x) is a unit translation or a rotation (x - centre) / size about a coordinate axis. Returns the mode count.
int RigidModeRow(int dim, const double *x, const double *centre, double size, const double *dir, double *row);

/// Smallest eigenvalue of the symmetric n x n matrix a (row major, n <= 6) relative to its largest one (1 when a
/// is zero: no information, treated as singular by the caller through its own count), by Jacobi rotations.
double RelativeSmallestEigenvalue(int n, const double *a);

class RigidModes {
public:
  /// Accumulates the Dirichlet rows (fixed[v*dim+k] marks a fixed dof) of the owned vertices, and the rows of every
  /// direction at every owned vertex (the matrix of FreeMotion's fit). Collective.
  [[nodiscard]] PetscErrorCode Setup(const Mesh &mesh, const std::vector<char> &fixed);
  /// Whether the Dirichlet rows and the active pairs (normals at their vertices) hold every rigid mode. Collective.
  [[nodiscard]] PetscErrorCode Held(const std::vector<PairKey> &keys, const std::vector<std::array<double, 3>> &normals,
                                    const std::vector<char> &active, bool &held) const;
  /// The rigid motion nearest to the displacement du (local vertex layout, du[v*dim+k]; least squares over the owned
  /// vertices) among those the Dirichlet rows and the active pairs leave free: its mode coefficients a (zero when
  /// every mode is held). Collective.
  [[nodiscard]] PetscErrorCode FreeMotion(const std::vector<PairKey> &keys,
                                          const std::vector<std::array<double, 3>> &normals,
                                          const std::vector<char> &active, const double *du,
                                          std::array<double, 6> &a) const;
  /// The displacement along dir at x of the rigid motion with mode coefficients a.
  double Along(const double *x, const double *dir, const std::array<double, 6> &a) const;
  /// The displacement v (dim values) at x of the rigid motion with mode coefficients a.
  void Motion(const double *x, const std::array<double, 6> &a, double *v) const;
  /// The size of a rigid motion: the norm of its coefficients (a rotation's is the displacement it gives at the
  /// body's size from its centre).
  double Magnitude(const std::array<double, 6> &a) const;

private:
  /// The Gram matrix of the Dirichlet rows and the active pairs' rows (nmodes_ x nmodes_). Collective.
  [[nodiscard]] PetscErrorCode Gram(const std::vector<PairKey> &keys, const std::vector<std::array<double, 3>> &normals,
                                    const std::vector<char> &active, std::array<double, 36> &gram) const;

  const Mesh *mesh_ = nullptr;
  int nmodes_ = 3;
  double centre_[3] = {0, 0, 0}, size_ = 1;
  std::array<double, 36> g_dirichlet_{};
  std::array<double, 36> m_vertices_{}; ///< sum over the vertices of the rows of every direction (the fit's matrix)
};

} // namespace signorini
