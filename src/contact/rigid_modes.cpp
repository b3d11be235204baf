// Rigid-body modes left free by the supports and the active contact constraints.
#include "signorini/contact/rigid_modes.hpp"

#include "signorini/core/symmetric_eigen.hpp"

#include <algorithm>
#include <cmath>

namespace signorini {

int RigidModeRow(int dim, const double *x, const double *centre, double size, const double *dir, double *row) {
  double r[3] = {0, 0, 0};
  for (int d = 0; d < dim; ++d) r[d] = (x[d] - centre[d]) / size;
  int n = 0;
  for (int d = 0; d < dim; ++d) row[n++] = dir[d];
  if (dim == 2) {
    row[n++] = -r[1] * dir[0] + r[0] * dir[1];
  } else {
    // Rotations about x, y, z: omega x r.
    row[n++] = -r[2] * dir[1] + r[1] * dir[2];
    row[n++] = r[2] * dir[0] - r[0] * dir[2];
    row[n++] = -r[1] * dir[0] + r[0] * dir[1];
  }
  return n;
}

double RelativeSmallestEigenvalue(int n, const double *a) {
  const std::vector<double> eig = SymmetricEigenvalues(std::vector<double>(a, a + n * n), n);
  const double hi = std::max(std::abs(eig.front()), std::abs(eig.back()));
  return hi > 0 ? eig.front() / hi : 0.0;
}

namespace {
/// A Gram matrix eigenvalue at most this fraction of the largest is a free mode: a mode held by a single row at
/// distance h from another has an eigenvalue of order (h / size)^2, far above it for any mesh; round-off is far below.
constexpr double FREE_MODE = 1e-12;

void AddRow(int n, const double *row, double *g) {
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) g[i * n + j] += row[i] * row[j];
}
} // namespace

PetscErrorCode RigidModes::Setup(const Mesh &mesh, const std::vector<char> &fixed) {
  const int dim = mesh.Dim();
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, glo[3], ghi[3];
  PetscFunctionBeginUser;
  mesh_ = &mesh;
  for (PetscInt v = 0; v < mesh.NumLocalVertices(); ++v)
    for (int d = 0; d < dim; ++d) lo[d] = std::min(lo[d], mesh.X(v)[d]), hi[d] = std::max(hi[d], mesh.X(v)[d]);
  PetscCallMPI(MPI_Allreduce(lo, glo, 3, MPI_DOUBLE, MPI_MIN, mesh.Comm()));
  PetscCallMPI(MPI_Allreduce(hi, ghi, 3, MPI_DOUBLE, MPI_MAX, mesh.Comm()));
  size_ = 0;
  for (int d = 0; d < dim; ++d) centre_[d] = 0.5 * (glo[d] + ghi[d]), size_ = std::max(size_, ghi[d] - glo[d]);
  size_ = size_ > 0 ? size_ : 1;
  std::array<double, 36> g{}, m{};
  double row[6];
  nmodes_ = dim == 2 ? 3 : 6;
  for (PetscInt v = 0; v < mesh.NumLocalVertices(); ++v) {
    if (!mesh.Owned(v)) continue;
    for (int k = 0; k < dim; ++k) {
      double e[3] = {0, 0, 0};
      e[k] = 1;
      RigidModeRow(dim, mesh.X(v), centre_, size_, e, row);
      AddRow(nmodes_, row, m.data());
      if (fixed[v * dim + k]) AddRow(nmodes_, row, g.data());
    }
  }
  PetscCallMPI(MPI_Allreduce(g.data(), g_dirichlet_.data(), 36, MPI_DOUBLE, MPI_SUM, mesh.Comm()));
  PetscCallMPI(MPI_Allreduce(m.data(), m_vertices_.data(), 36, MPI_DOUBLE, MPI_SUM, mesh.Comm()));
  PetscFunctionReturn(0);
}

PetscErrorCode RigidModes::Gram(const std::vector<PairKey> &keys, const std::vector<std::array<double, 3>> &normals,
                                const std::vector<char> &active, std::array<double, 36> &gram) const {
  std::array<double, 36> g{};
  double row[6];
  PetscFunctionBeginUser;
  for (std::size_t p = 0; p < keys.size(); ++p)
    if (active[p]) {
      RigidModeRow(mesh_->Dim(), mesh_->X(keys[p].vertex), centre_, size_, normals[p].data(), row);
      AddRow(nmodes_, row, g.data());
    }
  PetscCallMPI(MPI_Allreduce(g.data(), gram.data(), 36, MPI_DOUBLE, MPI_SUM, mesh_->Comm()));
  for (int i = 0; i < 36; ++i) gram[i] += g_dirichlet_[i];
  PetscFunctionReturn(0);
}

PetscErrorCode RigidModes::Held(const std::vector<PairKey> &keys, const std::vector<std::array<double, 3>> &normals,
                                const std::vector<char> &active, bool &held) const {
  std::array<double, 36> gg;
  PetscFunctionBeginUser;
  PetscCall(Gram(keys, normals, active, gg));
  held = RelativeSmallestEigenvalue(nmodes_, gg.data()) > FREE_MODE;
  PetscFunctionReturn(0);
}

PetscErrorCode RigidModes::FreeMotion(const std::vector<PairKey> &keys,
                                      const std::vector<std::array<double, 3>> &normals,
                                      const std::vector<char> &active, const double *du,
                                      std::array<double, 6> &a) const {
  const int dim = mesh_->Dim(), n = nmodes_;
  std::array<double, 36> gg;
  std::array<double, 6> b{};
  double row[6];
  PetscFunctionBeginUser;
  PetscCall(Gram(keys, normals, active, gg));
  for (PetscInt v = 0; v < mesh_->NumLocalVertices(); ++v) {
    if (!mesh_->Owned(v)) continue;
    for (int k = 0; k < dim; ++k) {
      double e[3] = {0, 0, 0};
      e[k] = 1;
      RigidModeRow(dim, mesh_->X(v), centre_, size_, e, row);
      for (int i = 0; i < n; ++i) b[i] += row[i] * du[v * dim + k];
    }
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, b.data(), n, MPI_DOUBLE, MPI_SUM, mesh_->Comm()));
  // The free modes: the eigenvectors of the Gram matrix whose eigenvalues are below FREE_MODE of the largest (as in
  // Held). The fit a = F c minimises sum_v |du(v) - m(v) F c|^2: (F^T M F) c = F^T b, M the vertices' Gram matrix.
  std::vector<double> vec;
  const std::vector<double> eig = SymmetricEigen(std::vector<double>(gg.begin(), gg.begin() + n * n), n, &vec);
  double top = 0;
  for (double e : eig) top = std::max(top, std::abs(e));
  std::vector<int> free;
  for (int j = 0; j < n; ++j)
    if (eig[j] <= FREE_MODE * top) free.push_back(j);
  const int f = (int)free.size();
  std::vector<double> lhs(f * f, 0.0), rhs(f, 0.0);
  for (int i = 0; i < f; ++i) {
    for (int r = 0; r < n; ++r) rhs[i] += vec[r * n + free[i]] * b[r];
    for (int j = 0; j < f; ++j)
      for (int r = 0; r < n; ++r)
        for (int s = 0; s < n; ++s) lhs[i * f + j] += vec[r * n + free[i]] * m_vertices_[r * n + s] * vec[s * n + free[j]];
  }
  // Gaussian elimination of the small symmetric positive definite system (no pivoting needed).
  for (int i = 0; i < f; ++i)
    for (int j = i + 1; j < f; ++j) {
      const double l = lhs[j * f + i] / lhs[i * f + i];
      for (int k = i; k < f; ++k) lhs[j * f + k] -= l * lhs[i * f + k];
      rhs[j] -= l * rhs[i];
    }
  for (int i = f - 1; i >= 0; --i) {
    for (int k = i + 1; k < f; ++k) rhs[i] -= lhs[i * f + k] * rhs[k];
    rhs[i] /= lhs[i * f + i];
  }
  a.fill(0.0);
  for (int i = 0; i < f; ++i)
    for (int r = 0; r < n; ++r) a[r] += vec[r * n + free[i]] * rhs[i];
  PetscFunctionReturn(0);
}

double RigidModes::Along(const double *x, const double *dir, const std::array<double, 6> &a) const {
  double row[6], s = 0;
  RigidModeRow(mesh_->Dim(), x, centre_, size_, dir, row);
  for (int i = 0; i < nmodes_; ++i) s += row[i] * a[i];
  return s;
}

void RigidModes::Motion(const double *x, const std::array<double, 6> &a, double *v) const {
  for (int k = 0; k < mesh_->Dim(); ++k) {
    double e[3] = {0, 0, 0};
    e[k] = 1;
    v[k] = Along(x, e, a);
  }
}

double RigidModes::Magnitude(const std::array<double, 6> &a) const {
  double s = 0;
  for (int i = 0; i < nmodes_; ++i) s += a[i] * a[i];
  return std::sqrt(s);
}

} // namespace signorini
