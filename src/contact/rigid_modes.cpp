// Rigid-body modes left free by the supports and the active contact constraints.
#include "signorini/contact/rigid_modes.hpp"

#include "signorini/core/blocks.hpp"
#include "signorini/core/symmetric_eigen.hpp"
#include "signorini/linalg/lcp.hpp"

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

} // namespace

PetscErrorCode RigidModes::Setup(const Mesh &mesh, const std::vector<char> &fixed, const MortarCoupling *mortar) {
  const int dim = mesh.Dim();
  const PetscInt nb = std::max<PetscInt>(mesh.NumBodies(), 1);
  PetscFunctionBeginUser;
  mesh_ = &mesh;
  mortar_ = mortar;
  per_body_ = dim == 2 ? 3 : 6;
  n_ = per_body_ * (int)nb;
  // Each body's bounding box: its centre and size.
  std::vector<double> lo(3 * nb, INFINITY), hi(3 * nb, -INFINITY);
  for (PetscInt v = 0; v < mesh.NumLocalVertices(); ++v) {
    const PetscInt b = mesh.NumBodies() > 0 ? mesh.VertexBody(v) : 0;
    for (int d = 0; d < dim; ++d)
      lo[3 * b + d] = std::min(lo[3 * b + d], mesh.X(v)[d]), hi[3 * b + d] = std::max(hi[3 * b + d], mesh.X(v)[d]);
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, lo.data(), (int)lo.size(), MPI_DOUBLE, MPI_MIN, mesh.Comm()));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, hi.data(), (int)hi.size(), MPI_DOUBLE, MPI_MAX, mesh.Comm()));
  centre_.assign(3 * nb, 0.0);
  size_.assign(nb, 0.0);
  for (PetscInt b = 0; b < nb; ++b) {
    for (int d = 0; d < dim; ++d)
      centre_[3 * b + d] = 0.5 * (lo[3 * b + d] + hi[3 * b + d]), size_[b] = std::max(size_[b], hi[3 * b + d] - lo[3 * b + d]);
    size_[b] = size_[b] > 0 ? size_[b] : 1;
  }
  g_dirichlet_.assign(n_ * n_, 0.0);
  m_vertices_.assign(n_ * n_, 0.0);
  std::vector<std::pair<int, double>> row;
  for (PetscInt v = 0; v < mesh.NumLocalVertices(); ++v) {
    if (!mesh.Owned(v)) continue;
    for (int k = 0; k < dim; ++k) {
      double e[3] = {0, 0, 0};
      e[k] = 1;
      row.clear();
      AppendModes(mesh.NumBodies() > 0 ? mesh.VertexBody(v) : 0, mesh.X(v), e, 1, row);
      AddRow(row, m_vertices_);
      if (fixed[v * dim + k]) AddRow(row, g_dirichlet_);
    }
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, g_dirichlet_.data(), n_ * n_, MPI_DOUBLE, MPI_SUM, mesh.Comm()));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, m_vertices_.data(), n_ * n_, MPI_DOUBLE, MPI_SUM, mesh.Comm()));
  PetscFunctionReturn(0);
}

void RigidModes::AddRow(const std::vector<std::pair<int, double>> &row, std::vector<double> &g) const {
  for (const auto &[i, a] : row)
    for (const auto &[j, b] : row) g[i * n_ + j] += a * b;
}

void RigidModes::AppendModes(PetscInt b, const double *x, const double *dir, double scale,
                             std::vector<std::pair<int, double>> &row) const {
  double m[6];
  const int n = RigidModeRow(mesh_->Dim(), x, &centre_[3 * b], size_[b], dir, m);
  for (int i = 0; i < n; ++i) row.emplace_back((int)b * per_body_ + i, scale * m[i]);
}

void RigidModes::PairRow(std::size_t p, const std::vector<PairKey> &keys,
                         const std::vector<std::array<double, 3>> &normals,
                         std::vector<std::pair<int, double>> &row, std::size_t terms_of) const {
  const PetscInt v = keys[p].vertex;
  row.clear();
  AppendModes(mesh_->NumBodies() > 0 ? mesh_->VertexBody(v) : 0, mesh_->X(v), normals[p].data(), 1, row);
  const auto *terms = mortar_ ? mortar_->Terms(terms_of) : nullptr;
  if (terms)
    for (const auto &t : *terms) AppendModes(t.body, t.x, normals[p].data(), -t.w, row);
}

PetscErrorCode RigidModes::Gram(const std::vector<PairKey> &keys, const std::vector<std::array<double, 3>> &normals,
                                const std::vector<char> &active, std::vector<double> &gram,
                                const std::vector<std::size_t> *pair_of) const {
  std::vector<std::pair<int, double>> row;
  PetscFunctionBeginUser;
  gram.assign(n_ * n_, 0.0);
  for (std::size_t p = 0; p < keys.size(); ++p)
    if (active[p]) {
      PairRow(p, keys, normals, row, pair_of ? (*pair_of)[p] : p);
      AddRow(row, gram);
    }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, gram.data(), n_ * n_, MPI_DOUBLE, MPI_SUM, mesh_->Comm()));
  for (int i = 0; i < n_ * n_; ++i) gram[i] += g_dirichlet_[i];
  PetscFunctionReturn(0);
}

std::vector<int> RigidModes::FreeModes(const std::vector<double> &gram, std::vector<double> &vec) const {
  const std::vector<double> eig = SymmetricEigen(gram, n_, &vec);
  double top = 0;
  for (double e : eig) top = std::max(top, std::abs(e));
  std::vector<int> free;
  for (int j = 0; j < n_; ++j)
    if (eig[j] <= FREE_MODE * top) free.push_back(j);
  return free;
}

PetscErrorCode RigidModes::OnModes(const double *field, std::vector<double> &out) const {
  const int dim = mesh_->Dim();
  std::vector<std::pair<int, double>> row;
  PetscFunctionBeginUser;
  out.assign(n_, 0.0);
  for (PetscInt v = 0; v < mesh_->NumLocalVertices(); ++v) {
    if (!mesh_->Owned(v)) continue;
    row.clear();
    AppendModes(mesh_->NumBodies() > 0 ? mesh_->VertexBody(v) : 0, mesh_->X(v), field + v * dim, 1, row);
    for (const auto &[i, m] : row) out[i] += m;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, out.data(), n_, MPI_DOUBLE, MPI_SUM, mesh_->Comm()));
  PetscFunctionReturn(0);
}

PetscErrorCode RigidModes::Held(const std::vector<PairKey> &keys, const std::vector<std::array<double, 3>> &normals,
                                const std::vector<char> &active, bool &held,
                                const std::vector<std::size_t> *pair_of) const {
  std::vector<double> gg;
  PetscFunctionBeginUser;
  PetscCall(Gram(keys, normals, active, gg, pair_of));
  held = RelativeSmallestEigenvalue(n_, gg.data()) > FREE_MODE;
  PetscFunctionReturn(0);
}

PetscErrorCode RigidModes::FreeMotion(const std::vector<PairKey> &keys,
                                      const std::vector<std::array<double, 3>> &normals,
                                      const std::vector<char> &active, const double *du, RigidMotion &a,
                                      const std::vector<std::size_t> *pair_of) const {
  const int n = n_;
  std::vector<double> gg, b;
  PetscFunctionBeginUser;
  PetscCall(Gram(keys, normals, active, gg, pair_of));
  PetscCall(OnModes(du, b));
  // The free modes of the Gram matrix (as in Held). The fit a = F c minimises sum_v |du(v) - m(v) F c|^2:
  // (F^T M F) c = F^T b, M the vertices' Gram matrix.
  std::vector<double> vec;
  const std::vector<int> free = FreeModes(gg, vec);
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
  a.assign(n, 0.0);
  for (int i = 0; i < f; ++i)
    for (int r = 0; r < n; ++r) a[r] += vec[r * n + free[i]] * rhs[i];
  PetscFunctionReturn(0);
}

PetscErrorCode RigidModes::Unbalanced(const std::vector<PairKey> &keys,
                                      const std::vector<std::array<double, 3>> &normals, const double *f,
                                      double &unbalanced) const {
  const int n = n_;
  std::vector<double> load;
  std::vector<std::pair<int, double>> row;
  PetscFunctionBeginUser;
  unbalanced = 0;
  // The load's generalised forces on the modes, and the modes that the supports leave free.
  PetscCall(OnModes(f, load));
  std::vector<double> vec;
  const std::vector<int> free = FreeModes(g_dirichlet_, vec);
  const int k = (int)free.size();
  std::vector<double> b(k, 0.0);
  double bnorm = 0;
  for (int i = 0; i < k; ++i) {
    for (int r = 0; r < n; ++r) b[i] -= vec[r * n + free[i]] * load[r];
    bnorm += b[i] * b[i];
  }
  bnorm = std::sqrt(bnorm);
  double fnorm = 0;
  for (double l : load) fnorm += l * l;
  if (k == 0 || !(bnorm > 1e-12 * std::sqrt(fnorm))) PetscFunctionReturn(0);
  // Every pair's forces on the free modes, gathered in rank order (k values per pair: linear in the pairs).
  std::vector<double> mine, A;
  for (std::size_t p = 0; p < keys.size(); ++p) {
    PairRow(p, keys, normals, row);
    std::vector<double> dense(n, 0.0);
    for (const auto &[i, m] : row) dense[i] += m;
    for (int i = 0; i < k; ++i) {
      double a = 0;
      for (int r = 0; r < n; ++r) a += vec[r * n + free[i]] * dense[r];
      mine.push_back(a);
    }
  }
  PetscCall(AllGather(mesh_->Comm(), mine, A));
  std::vector<double> lambda;
  unbalanced = NonNegativeLeastSquares(k, (int)(A.size() / k), A, b, lambda) / bnorm;
  PetscFunctionReturn(0);
}

double RigidModes::PairRate(std::size_t p, const std::vector<PairKey> &keys,
                            const std::vector<std::array<double, 3>> &normals, const RigidMotion &a) const {
  std::vector<std::pair<int, double>> row;
  PairRow(p, keys, normals, row);
  double s = 0;
  for (const auto &[i, m] : row) s += m * a[i];
  return s;
}

void RigidModes::Motion(PetscInt vertex, const RigidMotion &a, double *v) const {
  std::vector<std::pair<int, double>> row;
  for (int k = 0; k < mesh_->Dim(); ++k) {
    double e[3] = {0, 0, 0};
    e[k] = 1;
    row.clear();
    AppendModes(mesh_->NumBodies() > 0 ? mesh_->VertexBody(vertex) : 0, mesh_->X(vertex), e, 1, row);
    v[k] = 0;
    for (const auto &[i, m] : row) v[k] += m * a[i];
  }
}

double RigidModes::Magnitude(const RigidMotion &a) const {
  double s = 0;
  for (double c : a) s += c * c;
  return std::sqrt(s);
}

} // namespace signorini
