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
  std::array<double, 36> g{};
  double row[6];
  for (PetscInt v = 0; v < mesh.NumLocalVertices(); ++v) {
    if (!mesh.Owned(v)) continue;
    for (int k = 0; k < dim; ++k) {
      if (!fixed[v * dim + k]) continue;
      double e[3] = {0, 0, 0};
      e[k] = 1;
      nmodes_ = RigidModeRow(dim, mesh.X(v), centre_, size_, e, row);
      AddRow(nmodes_, row, g.data());
    }
  }
  nmodes_ = dim == 2 ? 3 : 6;
  PetscCallMPI(MPI_Allreduce(g.data(), g_dirichlet_.data(), 36, MPI_DOUBLE, MPI_SUM, mesh.Comm()));
  PetscFunctionReturn(0);
}

PetscErrorCode RigidModes::Held(const std::vector<PairKey> &keys, const std::vector<std::array<double, 3>> &normals,
                                const std::vector<char> &active, bool &held) const {
  std::array<double, 36> g{}, gg;
  double row[6];
  PetscFunctionBeginUser;
  for (std::size_t p = 0; p < keys.size(); ++p)
    if (active[p]) {
      RigidModeRow(mesh_->Dim(), mesh_->X(keys[p].vertex), centre_, size_, normals[p].data(), row);
      AddRow(nmodes_, row, g.data());
    }
  PetscCallMPI(MPI_Allreduce(g.data(), gg.data(), 36, MPI_DOUBLE, MPI_SUM, mesh_->Comm()));
  for (int i = 0; i < 36; ++i) gg[i] += g_dirichlet_[i];
  // A mode held by a single row at distance h from another has an eigenvalue of order (h / size)^2; 1e-12 is far
  // below that for any mesh and far above round-off.
  held = RelativeSmallestEigenvalue(nmodes_, gg.data()) > 1e-12;
  PetscFunctionReturn(0);
}

} // namespace signorini
