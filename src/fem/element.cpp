// Reference elements, quadrature and element kernels (linear elasticity, St. Venant-Kirchhoff).
#include "signorini/fem/element.hpp"

#include <cmath>
#include <algorithm>
#include <cstring>

namespace signorini {

namespace {

/// Reference shape functions and derivatives at a point xi of the reference cell.
void ReferenceShape(int dim, int nodes, const double *xi, double *N, double (*dN)[MAX_DIM]) {
  if (dim == 2 && nodes == 3) {
    N[0] = 1 - xi[0] - xi[1], N[1] = xi[0], N[2] = xi[1];
    dN[0][0] = -1, dN[0][1] = -1, dN[1][0] = 1, dN[1][1] = 0, dN[2][0] = 0, dN[2][1] = 1;
  } else if (dim == 2 && nodes == 4) {
    const double s[4] = {-1, 1, 1, -1}, t[4] = {-1, -1, 1, 1};
    for (int a = 0; a < 4; ++a) {
      N[a] = 0.25 * (1 + s[a] * xi[0]) * (1 + t[a] * xi[1]);
      dN[a][0] = 0.25 * s[a] * (1 + t[a] * xi[1]);
      dN[a][1] = 0.25 * t[a] * (1 + s[a] * xi[0]);
    }
  } else if (dim == 3 && nodes == 4) {
    N[0] = 1 - xi[0] - xi[1] - xi[2], N[1] = xi[0], N[2] = xi[1], N[3] = xi[2];
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) dN[a][i] = a == 0 ? -1.0 : a == i + 1 ? 1.0 : 0.0;
  } else if (dim == 3 && nodes == 5) {
    // The linear pyramid (gmsh's: base 0-3 counter-clockwise seen from the apex 4) as the trilinear hexahedron with
    // its four top vertices collapsed onto the apex. In the pyramid's own coordinates (base [-1, 1]^2 at z = 0, apex
    // at z = 1; x = xi (1 - z), y = eta (1 - z), z = (1 + zeta) / 2) these are the rational functions of Bedrosian
    // (1992), N_a = ((1 - z) + s_a x + t_a y + s_a t_a x y / (1 - z)) / 4, N_apex = z: bilinear on the quadrilateral
    // base (conforming with hexahedra), linear on the triangular sides (conforming with tetrahedra), and they
    // reproduce every linear field. The collapsed map's Jacobian vanishes only at the apex (zeta = 1), which the
    // Gauss points of ReferenceQuadrature avoid.
    const double s[4] = {-1, 1, 1, -1}, t[4] = {-1, -1, 1, 1};
    for (int a = 0; a < 4; ++a) {
      const double fs = 1 + s[a] * xi[0], ft = 1 + t[a] * xi[1], fr = 1 - xi[2];
      N[a] = 0.125 * fs * ft * fr;
      dN[a][0] = 0.125 * s[a] * ft * fr;
      dN[a][1] = 0.125 * t[a] * fs * fr;
      dN[a][2] = -0.125 * fs * ft;
    }
    N[4] = 0.5 * (1 + xi[2]);
    dN[4][0] = dN[4][1] = 0, dN[4][2] = 0.5;
  } else if (dim == 3 && nodes == 8) {
    // gmsh's hexahedron: bottom (zeta = -1) and top counter-clockwise seen from +zeta, vertex a + 4 above a.
    const double s[8] = {-1, 1, 1, -1, -1, 1, 1, -1}, t[8] = {-1, -1, 1, 1, -1, -1, 1, 1},
                 r[8] = {-1, -1, -1, -1, 1, 1, 1, 1};
    for (int a = 0; a < 8; ++a) {
      const double fs = 1 + s[a] * xi[0], ft = 1 + t[a] * xi[1], fr = 1 + r[a] * xi[2];
      N[a] = 0.125 * fs * ft * fr;
      dN[a][0] = 0.125 * s[a] * ft * fr;
      dN[a][1] = 0.125 * t[a] * fs * fr;
      dN[a][2] = 0.125 * r[a] * fs * ft;
    }
  }
}

/// Quadrature rule on the reference cell: the centroid on the triangle and the tetrahedron (their shape functions are
/// linear, so every integrand here is constant on the cell (strain, stress, tangent and internal force, of both
/// models) or linear (a constant body force times N_a): one point integrates them exactly), 2x2 (2x2x2)
/// Gauss on the quadrilateral (hexahedron), and on the pyramid the 2x2x2 Gauss rule of the collapsed hexahedron: it
/// integrates the gradients of the shape functions exactly (their integrands adj(J)^T grad N are polynomials of
/// degree <= 2 in each reference coordinate, as on the hexahedron), so the patch test is passed on any pyramid, and
/// the volume of a pyramid exactly (det J is a polynomial of degree <= 2 in each coordinate).
int ReferenceQuadrature(int dim, int nodes, double (*xi)[MAX_DIM], double *w) {
  if (nodes == dim + 1) {
    for (int i = 0; i < dim; ++i) xi[0][i] = 1.0 / (dim + 1);
    w[0] = dim == 2 ? 1.0 / 2 : 1.0 / 6;
    return 1;
  }
  if (dim == 2 && nodes == 4) {
    const double g = 1.0 / std::sqrt(3.0);
    const double p[4][2] = {{-g, -g}, {g, -g}, {g, g}, {-g, g}};
    for (int q = 0; q < 4; ++q) xi[q][0] = p[q][0], xi[q][1] = p[q][1], w[q] = 1.0;
    return 4;
  }
  if (dim == 3 && (nodes == 5 || nodes == 8)) {
    const double g = 1.0 / std::sqrt(3.0);
    for (int q = 0; q < 8; ++q) {
      xi[q][0] = q & 1 ? g : -g, xi[q][1] = q & 2 ? g : -g, xi[q][2] = q & 4 ? g : -g;
      w[q] = 1.0;
    }
    return 8;
  }
  return 0;
}

double Det(int dim, const double J[MAX_DIM][MAX_DIM]) {
  if (dim == 2) return J[0][0] * J[1][1] - J[0][1] * J[1][0];
  return J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
         J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
}

void Inverse(int dim, const double J[MAX_DIM][MAX_DIM], double det, double Ji[MAX_DIM][MAX_DIM]) {
  if (dim == 2) {
    Ji[0][0] = J[1][1] / det, Ji[0][1] = -J[0][1] / det, Ji[1][0] = -J[1][0] / det, Ji[1][1] = J[0][0] / det;
    return;
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
      Ji[i][j] = (J[i1][j1] * J[i2][j2] - J[i1][j2] * J[i2][j1]) / det;
    }
}

/// Voigt index pairs: 2D (xx, yy, xy), 3D (xx, yy, zz, yz, xz, xy).
constexpr int VOIGT2[3][2] = {{0, 0}, {1, 1}, {0, 1}};
constexpr int VOIGT3[6][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};
int NumVoigt(int dim) { return dim == 2 ? 3 : 6; }
const int (*Voigt(int dim))[2] { return dim == 2 ? VOIGT2 : VOIGT3; }

} // namespace

void ElasticityMatrix(const Material &m, int dim, double D[6][6]) {
  const double lam = dim == 2 ? m.LambdaPlane() : m.Lambda3D(), mu = m.Mu();
  const int nv = NumVoigt(dim);
  std::memset(D, 0, sizeof(double) * 36);
  for (int i = 0; i < dim; ++i) {
    for (int j = 0; j < dim; ++j) D[i][j] = lam;
    D[i][i] = lam + 2 * mu;
  }
  for (int i = dim; i < nv; ++i) D[i][i] = mu;
}

namespace {

/// Displacement gradient H = grad u at quadrature point q.
void DisplacementGradient(const ElementGeometry &g, int q, const double *u, double H[MAX_DIM][MAX_DIM]) {
  for (int i = 0; i < g.dim; ++i)
    for (int j = 0; j < g.dim; ++j) H[i][j] = 0;
  for (int a = 0; a < g.nodes; ++a)
    for (int i = 0; i < g.dim; ++i)
      for (int j = 0; j < g.dim; ++j) H[i][j] += u[a * g.dim + i] * g.dN[q][a][j];
}

/// Deformation gradient F = I + H (identity for the linear model).
void DeformationGradient(int dim, const double H[MAX_DIM][MAX_DIM], bool large, double F[MAX_DIM][MAX_DIM]) {
  for (int i = 0; i < dim; ++i)
    for (int j = 0; j < dim; ++j) F[i][j] = (i == j ? 1.0 : 0.0) + (large ? H[i][j] : 0.0);
}

/// Strain in Voigt form with engineering shear from H: Green-Lagrange (large) or small strain.
void Strain(int dim, const double H[MAX_DIM][MAX_DIM], bool large, double eps[6]) {
  const int nv = NumVoigt(dim);
  for (int v = 0; v < nv; ++v) {
    const int i = Voigt(dim)[v][0], j = Voigt(dim)[v][1];
    double e = H[i][j] + H[j][i]; // Eq. 1: grad u + grad u^T (+ grad u^T grad u)
    if (large)
      for (int k = 0; k < dim; ++k) e += H[k][i] * H[k][j];
    eps[v] = i == j ? 0.5 * e : e;
  }
}

} // namespace

double MinDeformationJacobian(const ElementGeometry &g, const double *u) {
  double jmin = 1e300;
  for (int q = 0; q < g.nqp; ++q) {
    double H[MAX_DIM][MAX_DIM], F[MAX_DIM][MAX_DIM];
    DisplacementGradient(g, q, u, H);
    DeformationGradient(g.dim, H, true, F);
    jmin = std::min(jmin, Det(g.dim, F));
  }
  return jmin;
}

void FaceIntegrals(int dim, int n, const double *X, double *w, double (*an)[3]) {
  const auto x = [&](int a, int d) { return X[a * dim + d]; };
  if (n == dim) {
    // An edge (2D) or a triangle (3D): N_a integrates to 1 / n of the length or area.
    double A[3] = {0, 0, 0};
    if (dim == 2) {
      A[0] = x(1, 1) - x(0, 1), A[1] = -(x(1, 0) - x(0, 0));
    } else {
      double e1[3], e2[3];
      for (int d = 0; d < 3; ++d) e1[d] = x(1, d) - x(0, d), e2[d] = x(2, d) - x(0, d);
      A[0] = 0.5 * (e1[1] * e2[2] - e1[2] * e2[1]);
      A[1] = 0.5 * (e1[2] * e2[0] - e1[0] * e2[2]);
      A[2] = 0.5 * (e1[0] * e2[1] - e1[1] * e2[0]);
    }
    const double area = std::sqrt(A[0] * A[0] + A[1] * A[1] + A[2] * A[2]);
    for (int a = 0; a < n; ++a) {
      w[a] = area / n;
      for (int d = 0; d < 3; ++d) an[a][d] = A[d] / n;
    }
    return;
  }
  // A bilinear quadrilateral (3D): n dA = x_xi x x_eta dxi deta, 2x2 Gauss (exact for N_a x_xi x x_eta).
  const double s[4] = {-1, 1, 1, -1}, t[4] = {-1, -1, 1, 1}, g = 1.0 / std::sqrt(3.0);
  for (int a = 0; a < 4; ++a) {
    w[a] = 0;
    an[a][0] = an[a][1] = an[a][2] = 0;
  }
  for (int q = 0; q < 4; ++q) {
    const double xi = s[q] * g, eta = t[q] * g;
    double dxi[3] = {0, 0, 0}, deta[3] = {0, 0, 0};
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d) {
        dxi[d] += 0.25 * s[a] * (1 + t[a] * eta) * x(a, d);
        deta[d] += 0.25 * t[a] * (1 + s[a] * xi) * x(a, d);
      }
    const double da[3] = {dxi[1] * deta[2] - dxi[2] * deta[1], dxi[2] * deta[0] - dxi[0] * deta[2],
                          dxi[0] * deta[1] - dxi[1] * deta[0]};
    const double J = std::sqrt(da[0] * da[0] + da[1] * da[1] + da[2] * da[2]);
    for (int a = 0; a < 4; ++a) {
      const double N = 0.25 * (1 + s[a] * xi) * (1 + t[a] * eta);
      w[a] += N * J;
      for (int d = 0; d < 3; ++d) an[a][d] += N * da[d];
    }
  }
}

namespace {
/// The quadrature points and weights of a reference cell and its shape functions there, computed once.
template <int DIM, int NODES>
struct ReferenceCell {
  int nqp;
  double xi[MAX_QP][MAX_DIM], w[MAX_QP], N[MAX_QP][MAX_NODES], dN[MAX_QP][MAX_NODES][MAX_DIM] = {};
  ReferenceCell() : nqp(ReferenceQuadrature(DIM, NODES, xi, w)) {
    for (int q = 0; q < nqp; ++q) ReferenceShape(DIM, NODES, xi[q], N[q], dN[q]);
  }
};

/// ComputeGeometry for DIM and NODES known at compile time (the loops unrolled).
template <int DIM, int NODES>
bool ComputeGeometryFixed(const double *X, double thickness, ElementGeometry &g) {
  static const ReferenceCell<DIM, NODES> ref;
  g.dim = DIM;
  g.nodes = NODES;
  g.nqp = ref.nqp;
  g.min_detJ = 1e300;
  g.max_detJ = -1e300;
  for (int q = 0; q < g.nqp; ++q) {
    const auto &dNref = ref.dN[q];
    double J[MAX_DIM][MAX_DIM] = {}, Ji[MAX_DIM][MAX_DIM];
    for (int a = 0; a < NODES; ++a) g.N[q][a] = ref.N[q][a];
    for (int a = 0; a < NODES; ++a)
      for (int i = 0; i < DIM; ++i)
        for (int j = 0; j < DIM; ++j) J[i][j] += X[a * DIM + i] * dNref[a][j];
    const double det = Det(DIM, J);
    g.min_detJ = std::min(g.min_detJ, det);
    g.max_detJ = std::max(g.max_detJ, det);
    Inverse(DIM, J, det, Ji);
    for (int a = 0; a < NODES; ++a)
      for (int i = 0; i < DIM; ++i) {
        double d = 0;
        for (int j = 0; j < DIM; ++j) d += dNref[a][j] * Ji[j][i];
        g.dN[q][a][i] = d;
      }
    g.w[q] = ref.w[q] * std::abs(det) * (DIM == 2 ? thickness : 1.0);
  }
  return true;
}
} // namespace

bool ComputeGeometry(int dim, int nodes, const double *X, double thickness, ElementGeometry &g) {
  // The reference cells of ReferenceShape: the triangle and the quadrilateral, the tetrahedron, the pyramid and the
  // hexahedron.
  if (dim == 2 && nodes == 3) return ComputeGeometryFixed<2, 3>(X, thickness, g);
  if (dim == 2 && nodes == 4) return ComputeGeometryFixed<2, 4>(X, thickness, g);
  if (dim == 3 && nodes == 4) return ComputeGeometryFixed<3, 4>(X, thickness, g);
  if (dim == 3 && nodes == 5) return ComputeGeometryFixed<3, 5>(X, thickness, g);
  if (dim == 3 && nodes == 8) return ComputeGeometryFixed<3, 8>(X, thickness, g);
  g.dim = dim;
  g.nodes = nodes;
  g.nqp = 0;
  return false;
}

namespace {
/// ElementTangentAndForce for DIM and NODES known at compile time (the loops unrolled: the svk Newton iteration
/// assembles the tangent and the internal force at every step).
template <int DIM, int NODES>
double TangentAndForceFixed(const Material &m, const double (&D)[6][6], const ElementGeometry &g, const double *u,
                            double *K, double *f) {
  constexpr int n = NODES * DIM, nv = DIM == 2 ? 3 : 6;
  constexpr const int(*voigt)[2] = DIM == 2 ? VOIGT2 : VOIGT3;
  const bool large = m.model == MaterialModel::SVK;
  double jmin = 1e300;
  if (K) std::memset(K, 0, sizeof(double) * n * n);
  std::memset(f, 0, sizeof(double) * n);
  for (int q = 0; q < g.nqp; ++q) {
    const auto &dN = g.dN[q];
    double H[MAX_DIM][MAX_DIM], F[MAX_DIM][MAX_DIM], eps[6], S[nv] = {};
    DisplacementGradient(g, q, u, H);
    DeformationGradient(DIM, H, large, F);
    Strain(DIM, H, large, eps);
    if (large) jmin = std::min(jmin, Det(DIM, F));
    for (int a = 0; a < nv; ++a)
      for (int b = 0; b < nv; ++b) S[a] += D[a][b] * eps[b]; // Eq. 4: S = C : E
    // B[v][a*dim+k]: variation of the Voigt strain v with respect to u_ak, F^T grad N symmetrised.
    double B[nv][n];
    for (int v = 0; v < nv; ++v) {
      const int i = voigt[v][0], j = voigt[v][1];
      for (int a = 0; a < NODES; ++a)
        for (int k = 0; k < DIM; ++k)
          B[v][a * DIM + k] = i == j ? F[k][i] * dN[a][i] : F[k][i] * dN[a][j] + F[k][j] * dN[a][i];
    }
    const double wq = g.w[q];
    for (int r = 0; r < n; ++r) {
      double fr = 0;
      for (int v = 0; v < nv; ++v) fr += B[v][r] * S[v]; // Eq. 15: dE/du : S
      f[r] += wq * fr;
    }
    if (!K) continue;
    double DB[nv][n];
    for (int v = 0; v < nv; ++v)
      for (int c = 0; c < n; ++c) {
        double d = 0;
        for (int w = 0; w < nv; ++w) d += D[v][w] * B[w][c];
        DB[v][c] = wq * d;
      }
    // The tangent is symmetric (D and S are): its upper triangle here, mirrored after the last point (half the work
    // of the element's dominant loop).
    for (int r = 0; r < n; ++r)
      for (int c = r; c < n; ++c) {
        double kij = 0;
        for (int v = 0; v < nv; ++v) kij += B[v][r] * DB[v][c];
        K[r * n + c] += kij;
      }
    if (large) {
      // Geometric (initial-stress) term of Eq. 17: d2E/du2 : S = (grad N_a . S grad N_b) delta_ik.
      double Sm[DIM][DIM];
      for (int v = 0; v < nv; ++v) {
        const int i = voigt[v][0], j = voigt[v][1];
        Sm[i][j] = Sm[j][i] = wq * S[v];
      }
      for (int a = 0; a < NODES; ++a) {
        double SdN[DIM];
        for (int i = 0; i < DIM; ++i) {
          SdN[i] = 0;
          for (int j = 0; j < DIM; ++j) SdN[i] += Sm[i][j] * dN[a][j];
        }
        for (int b = a; b < NODES; ++b) {
          double gab = 0;
          for (int i = 0; i < DIM; ++i) gab += SdN[i] * dN[b][i];
          for (int k = 0; k < DIM; ++k) K[(a * DIM + k) * n + b * DIM + k] += gab;
        }
      }
    }
  }
  if (K)
    for (int r = 0; r < n; ++r)
      for (int c = r + 1; c < n; ++c) K[c * n + r] = K[r * n + c];
  return large ? jmin : 1.0;
}
} // namespace

double ElementTangentAndForce(const Material &m, const double (&D)[6][6], const ElementGeometry &g, const double *u,
                              double *K, double *f) {
  if (g.dim == 2 && g.nodes == 3) return TangentAndForceFixed<2, 3>(m, D, g, u, K, f);
  if (g.dim == 2 && g.nodes == 4) return TangentAndForceFixed<2, 4>(m, D, g, u, K, f);
  if (g.dim == 3 && g.nodes == 4) return TangentAndForceFixed<3, 4>(m, D, g, u, K, f);
  if (g.dim == 3 && g.nodes == 5) return TangentAndForceFixed<3, 5>(m, D, g, u, K, f);
  if (g.dim == 3 && g.nodes == 8) return TangentAndForceFixed<3, 8>(m, D, g, u, K, f);
  return 1.0;
}

double ElementTangentAndForce(const Material &m, const ElementGeometry &g, const double *u, double *K, double *f) {
  double D[6][6];
  ElasticityMatrix(m, g.dim, D);
  return ElementTangentAndForce(m, D, g, u, K, f);
}

CellStress ElementStress(const Material &m, const ElementGeometry &g, const double *u) {
  const int dim = g.dim, nv = NumVoigt(dim);
  const bool large = m.model == MaterialModel::SVK;
  double D[6][6];
  ElasticityMatrix(m, dim, D);
  CellStress out;
  double wsum = 0;
  for (int q = 0; q < g.nqp; ++q) {
    double H[MAX_DIM][MAX_DIM], F[MAX_DIM][MAX_DIM], eps[6], S[6] = {};
    DisplacementGradient(g, q, u, H);
    DeformationGradient(dim, H, large, F);
    Strain(dim, H, large, eps);
    for (int a = 0; a < nv; ++a)
      for (int b = 0; b < nv; ++b) S[a] += D[a][b] * eps[b];
    double Sm[MAX_DIM][MAX_DIM] = {}, sig[MAX_DIM][MAX_DIM] = {};
    for (int v = 0; v < nv; ++v) {
      const int i = Voigt(dim)[v][0], j = Voigt(dim)[v][1];
      Sm[i][j] = Sm[j][i] = S[v];
    }
    const double J = Det(dim, F);
    out.min_J = q == 0 ? J : std::min(out.min_J, J);
    for (int i = 0; i < dim; ++i)
      for (int j = 0; j < dim; ++j)
        for (int k = 0; k < dim; ++k)
          for (int l = 0; l < dim; ++l) sig[i][j] += F[i][k] * Sm[k][l] * F[j][l] / J;
    const double w = g.w[q];
    wsum += w;
    for (int v = 0; v < nv; ++v) {
      const int i = Voigt(dim)[v][0], j = Voigt(dim)[v][1];
      out.strain[v] += w * (i == j ? eps[v] : 0.5 * eps[v]);
      out.stress[v] += w * sig[i][j];
    }
    if (dim == 2 && !m.plane_stress) {
      // Plane strain: E_zz = 0, so S_zz = lambda tr E; F_zz = 1 gives sigma_zz = S_zz / J.
      out.stress_zz += w * m.Lambda3D() * (eps[0] + eps[1]) / J;
    }
  }
  for (int v = 0; v < nv; ++v) out.strain[v] /= wsum, out.stress[v] /= wsum;
  out.stress_zz /= wsum;
  if (dim == 2 && m.plane_stress) {
    // Plane stress: S_zz = lambda tr E + 2 mu E_zz = 0 with the 3D lambda (not LambdaPlane), so E_zz = -lambda /
    // (lambda + 2 mu) (E_xx + E_yy); the linear eps_zz = -nu / (1 - nu) (eps_xx + eps_yy) alike. Linear in the strain,
    // so the cell mean is the value of the mean. Output only: the svk kinematics keep F_zz = 1 (reference thickness).
    const double l = m.Lambda3D();
    out.strain_zz = -l / (l + 2.0 * m.Mu()) * (out.strain[0] + out.strain[1]);
  }
  const auto &s = out.stress;
  if (dim == 2) {
    const double sx = s[0], sy = s[1], sz = out.stress_zz, txy = s[2];
    out.von_mises = std::sqrt(0.5 * ((sx - sy) * (sx - sy) + (sy - sz) * (sy - sz) + (sz - sx) * (sz - sx)) +
                              3 * txy * txy);
  } else {
    out.von_mises = std::sqrt(0.5 * ((s[0] - s[1]) * (s[0] - s[1]) + (s[1] - s[2]) * (s[1] - s[2]) +
                                     (s[2] - s[0]) * (s[2] - s[0])) +
                              3 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
  }
  return out;
}

void ElementBodyForce(const ElementGeometry &g, const double *b, double *f) {
  std::memset(f, 0, sizeof(double) * g.nodes * g.dim);
  for (int q = 0; q < g.nqp; ++q)
    for (int a = 0; a < g.nodes; ++a)
      for (int k = 0; k < g.dim; ++k) f[a * g.dim + k] += g.w[q] * g.N[q][a] * b[k];
}

} // namespace signorini
