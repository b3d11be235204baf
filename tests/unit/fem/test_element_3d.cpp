// Element kernels in 3D (P1 tetrahedron, Q1 hexahedron and the linear pyramid with 2x2x2 Gauss): volume, symmetry,
// the six rigid modes and the rank of the stiffness, patch tests (mixed with pyramids too), the St. Venant-Kirchhoff
// tangent against finite differences, the small-load limit, frame indifference, det F, and the consistent face
// integrals of loads and tributary areas.
#include "signorini/fem/element.hpp"

#include "fem/element_test_util.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace signorini {
namespace {

using test::Difference;
using test::MatVec;
using test::MaxAbs;
using test::Norm;
using test::Random;
using test::SymmetricEigenvalues;
using test::Vector;

using Matrix3 = std::array<std::array<double, 3>, 3>;

struct Cell {
  std::string name;
  int nodes;
  Vector X; ///< 3 coordinates per vertex, gmsh order
  double volume;
};

/// Hexahedron vertices in gmsh order: bottom (z = 0) and top counter-clockwise seen from +z.
Vector HexCorners(const double lo[3], const double hi[3]) {
  const int bits[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  Vector X;
  for (const auto &b : bits)
    for (int d = 0; d < 3; ++d)
      X.push_back(b[d] ? hi[d] : lo[d]);
  return X;
}

const double ORIGIN[3] = {0, 0, 0}, ONE[3] = {1, 1, 1};
// Tetrahedron: volume det(x1 - x0, x2 - x0, x3 - x0) / 6, with the edges (1.2, 0.2, 0.05), (0.4, 1.4, 0.15),
// (0.2, 0.2, 1.15).
const Cell TETRAHEDRON{"tetrahedron", 4, {0.1, 0.2, 0.05, 1.3, 0.4, 0.1, 0.5, 1.6, 0.2, 0.3, 0.4, 1.2},
                       (1.2 * (1.4 * 1.15 - 0.15 * 0.2) - 0.2 * (0.4 * 1.15 - 0.15 * 0.2) +
                        0.05 * (0.4 * 0.2 - 1.4 * 0.2)) / 6};
const Cell CUBE{"unit cube", 8, HexCorners(ORIGIN, ONE), 1.0};
/// A cube with its corners moved (not an affine image of the cube): the volume is not checked.
Cell DistortedHex() {
  Cell c{"distorted hexahedron", 8, HexCorners(ORIGIN, ONE), -1};
  const double shift[8][3] = {{0.05, -0.1, 0.02}, {0.2, 0.05, -0.1}, {0.1, 0.15, 0.05}, {-0.1, 0.05, 0.1},
                              {0.02, 0.08, 0.2},  {0.1, -0.05, 0.3}, {0.25, 0.2, 0.1},  {-0.05, 0.1, 0.15}};
  for (int a = 0; a < 8; ++a)
    for (int d = 0; d < 3; ++d)
      c.X[3 * a + d] += shift[a][d];
  return c;
}
const Cell DISTORTED_HEX = DistortedHex();
// Pyramid (gmsh order: base counter-clockwise seen from the apex, apex last) on the unit square with its apex at
// height 0.8 off the centre: volume 0.8 / 3.
const Cell PYRAMID{"pyramid", 5, {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.3, 0.6, 0.8}, 0.8 / 3};
/// A pyramid with a warped (non-planar), non-parallelogram base and an oblique apex. Its volume, that of the
/// collapsed hexahedron x = (1 - z) B(xi, eta) + z apex over the bilinear base B, is 2x2x2 Gauss's own (exact).
Cell DistortedPyramid() {
  Cell c{"distorted pyramid", 5, PYRAMID.X, -1};
  const double shift[5][3] = {{0.05, -0.1, 0.02}, {0.2, 0.05, -0.1}, {0.1, 0.15, 0.08}, {-0.1, 0.05, -0.05},
                              {0.4, -0.2, 0.1}};
  for (int a = 0; a < 5; ++a)
    for (int d = 0; d < 3; ++d)
      c.X[3 * a + d] += shift[a][d];
  return c;
}
const Cell DISTORTED_PYRAMID = DistortedPyramid();
const Cell CELLS[] = {TETRAHEDRON, CUBE, DISTORTED_HEX, PYRAMID, DISTORTED_PYRAMID};

Material MakeMaterial(MaterialModel model = MaterialModel::LINEAR) {
  Material m;
  m.E = 200.0;
  m.nu = 0.3;
  m.model = model;
  return m;
}

std::string Describe(const Cell &cell, const Material &m) { return cell.name + ", " + m.ModelName(); }

ElementGeometry Geometry(const Cell &cell) {
  ElementGeometry g;
  EXPECT_TRUE(ComputeGeometry(3, cell.nodes, cell.X.data(), 1.0, g));
  return g;
}

void TangentAndForce(const Material &m, const Cell &cell, const Vector &u, Vector &K, Vector &f) {
  const int n = 3 * cell.nodes;
  K.assign(n * n, 0.0);
  f.assign(n, 0.0);
  const ElementGeometry g = Geometry(cell);
  ElementTangentAndForce(m, g, u.data(), K.data(), f.data());
}

Vector Stiffness(const Material &m, const Cell &cell) {
  Vector K, f;
  TangentAndForce(m, cell, Vector(3 * cell.nodes, 0.0), K, f);
  return K;
}

Vector Force(const Material &m, const Cell &cell, const Vector &u) {
  Vector K, f;
  TangentAndForce(m, cell, u, K, f);
  return f;
}

double Volume(const Cell &cell) {
  const ElementGeometry g = Geometry(cell);
  double v = 0;
  for (int q = 0; q < g.nqp; ++q)
    v += g.w[q];
  return v;
}

/// Nodal values of the displacement u(x) = a + B x.
Vector LinearField(const Vector &X, const double a[3], const Matrix3 &B) {
  Vector u(X.size());
  for (std::size_t k = 0; k < X.size() / 3; ++k)
    for (int i = 0; i < 3; ++i)
      u[3 * k + i] = a[i] + B[i][0] * X[3 * k] + B[i][1] * X[3 * k + 1] + B[i][2] * X[3 * k + 2];
  return u;
}

/// The six rigid-body modes of the linear theory: three translations, three infinitesimal rotations.
std::vector<Vector> RigidModes(const Vector &X) {
  const std::size_t n = X.size();
  std::vector<Vector> modes(6, Vector(n, 0.0));
  for (std::size_t k = 0; k < n / 3; ++k) {
    const double x = X[3 * k], y = X[3 * k + 1], z = X[3 * k + 2];
    for (int i = 0; i < 3; ++i)
      modes[i][3 * k + i] = 1.0;
    modes[3][3 * k + 1] = -z, modes[3][3 * k + 2] = y;
    modes[4][3 * k + 0] = z, modes[4][3 * k + 2] = -x;
    modes[5][3 * k + 0] = -y, modes[5][3 * k + 1] = x;
  }
  return modes;
}

/// Hand formula: Cauchy stress of the linear law, sigma = lambda tr(eps) I + 2 mu eps.
Matrix3 HookeStress(const Material &m, const Matrix3 &eps) {
  const double lambda = m.E * m.nu / ((1 + m.nu) * (1 - 2 * m.nu)), mu = m.E / (2 * (1 + m.nu));
  Matrix3 s{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      s[i][j] = 2 * mu * eps[i][j] + (i == j ? lambda * (eps[0][0] + eps[1][1] + eps[2][2]) : 0.0);
  return s;
}

/// Voigt pairs of the kernels' 3D output: xx, yy, zz, yz, xz, xy.
constexpr int VOIGT[6][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};

TEST(ElementGeometry3D, WeightsSumToTheVolumeAndShapeFunctionsArePartitionsOfUnity) {
  for (const Cell &cell : CELLS) {
    SCOPED_TRACE(cell.name);
    const ElementGeometry g = Geometry(cell);
    EXPECT_EQ(g.nqp, cell.nodes == 4 ? 1 : 8); // the centroid on the tetrahedron (linear shape functions)
    if (cell.volume > 0) {
      EXPECT_NEAR(Volume(cell), cell.volume, 1e-14);
    }
    EXPECT_GT(g.min_detJ, 0.0);
    for (int q = 0; q < g.nqp; ++q) {
      double N = 0, d[3] = {0, 0, 0};
      for (int a = 0; a < g.nodes; ++a) {
        N += g.N[q][a];
        for (int i = 0; i < 3; ++i)
          d[i] += g.dN[q][a][i];
      }
      EXPECT_NEAR(N, 1.0, 1e-14);
      for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(d[i], 0.0, 1e-13);
    }
  }
  // A parallelepiped (affine image of the cube) has volume |det A|.
  Cell sheared = CUBE;
  for (int a = 0; a < 8; ++a)
    sheared.X[3 * a] += 0.5 * sheared.X[3 * a + 2], sheared.X[3 * a + 1] *= 2;
  EXPECT_NEAR(Volume(sheared), 2.0, 1e-14);
  ElementGeometry g;
  EXPECT_FALSE(ComputeGeometry(3, 6, TETRAHEDRON.X.data(), 1.0, g)); // a prism is not a cell of signorini
}

TEST(ElementGeometry3D, PyramidVolumeIsThatEnclosedByItsFaces) {
  // Divergence theorem: V = 1/3 of the flux of x through the boundary, sum over the faces of x_a . int N_a n dA
  // (FaceIntegrals, exact on the bilinear base), the faces oriented outwards.
  const int faces[5][4] = {{0, 3, 2, 1}, {0, 1, 4, -1}, {1, 2, 4, -1}, {2, 3, 4, -1}, {3, 0, 4, -1}};
  for (const Cell &cell : {PYRAMID, DISTORTED_PYRAMID}) {
    SCOPED_TRACE(cell.name);
    double flux = 0;
    for (const auto &face : faces) {
      const int n = face[3] < 0 ? 3 : 4;
      double X[12], w[4], an[4][3];
      for (int a = 0; a < n; ++a)
        for (int d = 0; d < 3; ++d)
          X[3 * a + d] = cell.X[3 * face[a] + d];
      FaceIntegrals(3, n, X, w, an);
      for (int a = 0; a < n; ++a)
        for (int d = 0; d < 3; ++d)
          flux += X[3 * a + d] * an[a][d];
    }
    EXPECT_NEAR(Volume(cell), flux / 3, 1e-14);
  }
}

TEST(LinearElement3D, StiffnessIsSymmetricWithExactlySixZeroEigenvaluesTheRigidModes) {
  for (const Cell &cell : CELLS) {
    const Material m = MakeMaterial();
    SCOPED_TRACE(Describe(cell, m));
    const Vector K = Stiffness(m, cell);
    const int n = 3 * cell.nodes;
    double asym = 0;
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c)
        asym = std::max(asym, std::abs(K[r * n + c] - K[c * n + r]));
    EXPECT_LE(asym, 1e-12 * MaxAbs(K));
    const auto modes = RigidModes(cell.X);
    for (std::size_t k = 0; k < modes.size(); ++k)
      EXPECT_LE(Norm(MatVec(K, modes[k])), 1e-12 * Norm(K) * Norm(modes[k])) << "rigid mode " << k;
    const Vector eig = SymmetricEigenvalues(K, n);
    for (int i = 0; i < 6; ++i)
      EXPECT_LE(std::abs(eig[i]), 1e-12 * eig.back()) << "eigenvalue " << i;
    for (int i = 6; i < n; ++i)
      EXPECT_GT(eig[i], 1e-4 * eig.back()) << "eigenvalue " << i;
  }
}

TEST(LinearElement3D, PatchTestGivesExactConstantStrainAndStress) {
  const double a[3] = {0.3, -0.2, 0.1};
  const Matrix3 B{{{1.0e-3, 2.0e-3, -1.5e-3}, {-0.5e-3, 3.0e-3, 0.7e-3}, {0.4e-3, -1.1e-3, 2.2e-3}}};
  Matrix3 eps{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      eps[i][j] = 0.5 * (B[i][j] + B[j][i]);
  const Material m = MakeMaterial();
  const Matrix3 sigma = HookeStress(m, eps);
  for (const Cell &cell : CELLS) {
    SCOPED_TRACE(cell.name);
    const Vector u = LinearField(cell.X, a, B);
    const CellStress s = ElementStress(m, Geometry(cell), u.data());
    for (int v = 0; v < 6; ++v) {
      const int i = VOIGT[v][0], j = VOIGT[v][1];
      EXPECT_NEAR(s.strain[v], eps[i][j], 1e-13) << "strain component " << v;
      EXPECT_NEAR(s.stress[v], sigma[i][j], 1e-10 * m.E * 3e-3) << "stress component " << v;
    }
    const double vm = std::sqrt(0.5 * (std::pow(sigma[0][0] - sigma[1][1], 2) + std::pow(sigma[1][1] - sigma[2][2], 2) +
                                       std::pow(sigma[2][2] - sigma[0][0], 2)) +
                                3 * (sigma[1][2] * sigma[1][2] + sigma[0][2] * sigma[0][2] + sigma[0][1] * sigma[0][1]));
    EXPECT_NEAR(s.von_mises, vm, 1e-10 * vm);
  }
}

/// A 2x2x2 block of cells on [0,2]^3 whose centre node is moved off the grid: eight distorted hexahedra; or each of
/// them cut into six tetrahedra along its diagonal (Kuhn's subdivision, conforming between neighbours); or the
/// hexahedra with every other one cut into six pyramids on its faces around a node near its centre (their bases,
/// warped by the moved centre node, are conforming with the neighbouring hexahedra's faces, their triangular sides
/// with each other).
enum class PatchCells { HEXAHEDRA, TETRAHEDRA, HEXAHEDRA_AND_PYRAMIDS };

struct Patch {
  Vector X;
  std::vector<std::vector<int>> cells;
  std::vector<int> interior{13};
};

/// The faces of a hexahedron (gmsh order) as pyramid bases, counter-clockwise seen from the hexahedron's inside.
constexpr int HEX_FACES_INWARD[6][4] = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1},
                                        {3, 2, 6, 7}, {0, 3, 7, 4}, {1, 5, 6, 2}};

Patch MakePatch(PatchCells kind) {
  Patch p;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        const bool centre = i == 1 && j == 1 && k == 1;
        p.X.insert(p.X.end(), {i + (centre ? 0.13 : 0.0), j - (centre ? 0.08 : 0.0), k + (centre ? 0.11 : 0.0)});
      }
  const auto node = [](int i, int j, int k) { return i + 3 * j + 9 * k; };
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const std::vector<int> hex{node(i, j, k),         node(i + 1, j, k),         node(i + 1, j + 1, k),
                                   node(i, j + 1, k),     node(i, j, k + 1),         node(i + 1, j, k + 1),
                                   node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)};
        if (kind == PatchCells::HEXAHEDRA || (kind == PatchCells::HEXAHEDRA_AND_PYRAMIDS && (i + j + k) % 2 == 0)) {
          p.cells.push_back(hex);
          continue;
        }
        if (kind == PatchCells::HEXAHEDRA_AND_PYRAMIDS) {
          const int apex = (int)p.X.size() / 3;
          p.X.insert(p.X.end(), {i + 0.47, j + 0.55, k + 0.52});
          p.interior.push_back(apex);
          for (const auto &face : HEX_FACES_INWARD)
            p.cells.push_back({hex[face[0]], hex[face[1]], hex[face[2]], hex[face[3]], apex});
          continue;
        }
        for (const auto &perm : perms) {
          int c[3] = {i, j, k};
          std::vector<int> tet{node(c[0], c[1], c[2])};
          for (int axis : perm) {
            c[axis]++;
            tet.push_back(node(c[0], c[1], c[2]));
          }
          p.cells.push_back(tet);
        }
      }
  return p;
}

/// The patch's cell e with its vertices' coordinates.
Cell PatchCell(const Patch &p, const std::vector<int> &nodes) {
  Cell cell{"patch cell", (int)nodes.size(), {}, -1};
  for (int v : nodes)
    for (int d = 0; d < 3; ++d)
      cell.X.push_back(p.X[3 * v + d]);
  return cell;
}

Vector AssemblePatchForce(const Material &m, const Patch &p, const Vector &u) {
  Vector f(p.X.size(), 0.0);
  for (const auto &nodes : p.cells) {
    const Cell cell = PatchCell(p, nodes);
    Vector ue;
    for (int v : nodes)
      for (int d = 0; d < 3; ++d)
        ue.push_back(u[3 * v + d]);
    const Vector fe = Force(m, cell, ue);
    for (std::size_t a = 0; a < nodes.size(); ++a)
      for (int d = 0; d < 3; ++d)
        f[3 * nodes[a] + d] += fe[3 * a + d];
  }
  return f;
}

TEST(Element3D, PatchTestInteriorForcesCancelForLinearAndSvk) {
  const double a[3] = {0.3, -0.2, 0.1};
  const Matrix3 B{{{0.15, 0.1, -0.05}, {-0.05, -0.12, 0.08}, {0.06, 0.04, 0.1}}};
  const char *names[] = {"hexahedra", "tetrahedra", "hexahedra and pyramids"};
  for (PatchCells kind : {PatchCells::HEXAHEDRA, PatchCells::TETRAHEDRA, PatchCells::HEXAHEDRA_AND_PYRAMIDS})
    for (MaterialModel model : {MaterialModel::LINEAR, MaterialModel::SVK}) {
      const Patch patch = MakePatch(kind);
      const Material m = MakeMaterial(model);
      SCOPED_TRACE(std::string(names[(int)kind]) + ", " + m.ModelName());
      double volume = 0;
      for (const auto &nodes : patch.cells) {
        const ElementGeometry g = Geometry(PatchCell(patch, nodes));
        // No cell folded (Kuhn's tetrahedra alternate in orientation, which the kernels do not mind); the pyramids
        // are in gmsh's order.
        EXPECT_GT(nodes.size() == 5 ? g.min_detJ : g.min_detJ * g.max_detJ, 0.0);
        for (int q = 0; q < g.nqp; ++q)
          volume += g.w[q];
      }
      EXPECT_NEAR(volume, 8.0, 1e-13); // the cells tile the block
      const Vector f = AssemblePatchForce(m, patch, LinearField(patch.X, a, B));
      const double scale = MaxAbs(f);
      ASSERT_GT(scale, 0.0);
      for (int v : patch.interior)
        for (int d = 0; d < 3; ++d)
          EXPECT_NEAR(f[3 * v + d], 0.0, 1e-12 * scale) << "node " << v << ", component " << d;
    }
}

/// Random displacement of amplitude 0.1 times the element size.
Vector RandomDisplacement(const Cell &cell, Random &random) {
  const double h = std::cbrt(Volume(cell));
  Vector u(3 * cell.nodes);
  for (double &x : u)
    x = 0.1 * h * random.Next();
  return u;
}

TEST(SvkElement3D, TangentMatchesCentralFiniteDifferenceOfTheForce) {
  Random random;
  for (const Cell &cell : {TETRAHEDRON, DISTORTED_HEX, DISTORTED_PYRAMID}) {
    const Material m = MakeMaterial(MaterialModel::SVK);
    SCOPED_TRACE(Describe(cell, m));
    const int n = 3 * cell.nodes;
    const Vector u = RandomDisplacement(cell, random);
    ASSERT_GT(ElementStress(m, Geometry(cell), u.data()).min_J, 0.5);
    Vector K, f;
    TangentAndForce(m, cell, u, K, f);
    const double h = 1e-6 * std::cbrt(Volume(cell));
    const Vector K_fd = test::CentralDifferenceJacobian(u, h, [&](const Vector &v) { return Force(m, cell, v); });
    EXPECT_LE(Norm(Difference(K, K_fd)), 1e-6 * Norm(K));
    EXPECT_GT(Norm(Difference(K, Stiffness(MakeMaterial(), cell))), 1e-2 * Norm(K));
    EXPECT_LE(test::MaxAsymmetry(K, n), 1e-12 * MaxAbs(K));
  }
}

TEST(SvkElement3D, ReducesToLinearForSmallDisplacements) {
  Random random;
  const double epsilon = 1e-7;
  for (const Cell &cell : CELLS) {
    const Material svk = MakeMaterial(MaterialModel::SVK), linear = MakeMaterial();
    SCOPED_TRACE(cell.name);
    const Vector u = RandomDisplacement(cell, random);
    Vector small(u);
    for (double &x : small)
      x *= epsilon;
    Vector f_svk = Force(svk, cell, small);
    for (double &x : f_svk)
      x /= epsilon;
    const Vector f_lin = Force(linear, cell, u);
    EXPECT_LE(Norm(Difference(f_svk, f_lin)), 1e-6 * Norm(f_lin));
    EXPECT_LE(Norm(Difference(Stiffness(svk, cell), Stiffness(linear, cell))), 1e-12 * Norm(Stiffness(linear, cell)));
  }
}

TEST(SvkElement3D, FiniteRigidRotationIsStressFreeAndUniaxialStretchMatchesHand) {
  // Rotation by 40 degrees about the axis (1, 2, 2) / 3 (Rodrigues: R = I + sin t [k]x + (1 - cos t) [k]x^2).
  const double t = 40 * M_PI / 180, k[3] = {1.0 / 3, 2.0 / 3, 2.0 / 3}, a[3] = {0.4, -0.7, 0.2};
  const double Kx[3][3] = {{0, -k[2], k[1]}, {k[2], 0, -k[0]}, {-k[1], k[0], 0}};
  Matrix3 R_minus_I{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double k2 = 0;
      for (int l = 0; l < 3; ++l)
        k2 += Kx[i][l] * Kx[l][j];
      R_minus_I[i][j] = std::sin(t) * Kx[i][j] + (1 - std::cos(t)) * k2;
    }
  const double stretch = 1.2, E_xx = 0.5 * (stretch * stretch - 1);
  const Matrix3 S{{{stretch - 1, 0, 0}, {0, 0, 0}, {0, 0, 0}}};
  const Material svk = MakeMaterial(MaterialModel::SVK);
  const double lambda = svk.Lambda3D(), mu = svk.Mu();
  for (const Cell &cell : CELLS) {
    SCOPED_TRACE(cell.name);
    const Vector u = LinearField(cell.X, a, R_minus_I);
    EXPECT_LE(Norm(Force(svk, cell, u)), 1e-12 * Norm(Stiffness(MakeMaterial(), cell)) * Norm(u));
    const CellStress rot = ElementStress(svk, Geometry(cell), u.data());
    for (int v = 0; v < 6; ++v)
      EXPECT_NEAR(rot.stress[v], 0.0, 1e-12 * svk.E) << "component " << v;
    EXPECT_NEAR(rot.min_J, 1.0, 1e-14);
    // sigma = F S F^T / J with F = diag(stretch, 1, 1): sigma_xx = stretch S_xx, sigma_yy = sigma_zz = S_yy / stretch.
    const CellStress st = ElementStress(svk, Geometry(cell), LinearField(cell.X, a, S).data());
    EXPECT_NEAR(st.strain[0], E_xx, 1e-12);
    EXPECT_NEAR(st.stress[0], stretch * (lambda + 2 * mu) * E_xx, 1e-10 * svk.E);
    EXPECT_NEAR(st.stress[1], lambda * E_xx / stretch, 1e-10 * svk.E);
    EXPECT_NEAR(st.stress[2], lambda * E_xx / stretch, 1e-10 * svk.E);
    EXPECT_NEAR(st.min_J, stretch, 1e-13);
  }
}

TEST(Element3D, DeformationJacobianIsNegativeForAnInvertingDisplacement) {
  for (const Cell &cell : CELLS) {
    SCOPED_TRACE(cell.name);
    const ElementGeometry g = Geometry(cell);
    const double a[3] = {0, 0, 0};
    // u = -2 X: F = -I, det F = -1 (in 3D a point reflection turns the cell inside out).
    const Matrix3 flip{{{-2, 0, 0}, {0, -2, 0}, {0, 0, -2}}};
    EXPECT_NEAR(MinDeformationJacobian(g, LinearField(cell.X, a, flip).data()), -1.0, 1e-13);
    const Matrix3 squash{{{0, 0, 0}, {0, 0, 0}, {0, 0, -0.5}}};
    EXPECT_NEAR(MinDeformationJacobian(g, LinearField(cell.X, a, squash).data()), 0.5, 1e-13);
  }
}

TEST(Element3D, BodyForceDistributesTheTotalLoad) {
  const double b[3] = {0.5, -2.0, 1.5};
  for (const Cell &cell : CELLS) {
    SCOPED_TRACE(cell.name);
    const ElementGeometry g = Geometry(cell);
    Vector f(3 * cell.nodes);
    ElementBodyForce(g, b, f.data());
    for (int d = 0; d < 3; ++d) {
      double sum = 0;
      for (int a = 0; a < cell.nodes; ++a)
        sum += f[3 * a + d];
      EXPECT_NEAR(sum, b[d] * Volume(cell), 1e-13);
    }
  }
}

TEST(FaceIntegrals, EdgesTrianglesAndQuadrilateralsIntegrateAreaAndNormal) {
  double w[4], an[4][3];
  // 2D edge (0,0) -> (3,4): half the length each, normal (dy, -dx) / 2 (outward with the body on the left).
  const double edge[4] = {0, 0, 3, 4};
  FaceIntegrals(2, 2, edge, w, an);
  for (int a = 0; a < 2; ++a) {
    EXPECT_DOUBLE_EQ(w[a], 2.5);
    EXPECT_DOUBLE_EQ(an[a][0], 2.0);
    EXPECT_DOUBLE_EQ(an[a][1], -1.5);
  }
  // Triangle in the plane z = 1, counter-clockwise seen from +z: area 2, a third each, normal +z.
  const double tri[9] = {0, 0, 1, 2, 0, 1, 0, 2, 1};
  FaceIntegrals(3, 3, tri, w, an);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(w[a], 2.0 / 3, 1e-15);
    EXPECT_NEAR(an[a][2], 2.0 / 3, 1e-15);
    EXPECT_NEAR(std::abs(an[a][0]) + std::abs(an[a][1]), 0.0, 1e-15);
  }
  // Parallelogram: a quarter of the area each.
  const double para[12] = {0, 0, 0, 2, 0, 0, 3, 1, 0, 1, 1, 0};
  FaceIntegrals(3, 4, para, w, an);
  for (int a = 0; a < 4; ++a) {
    EXPECT_NEAR(w[a], 0.5, 1e-15);
    EXPECT_NEAR(an[a][2], 0.5, 1e-15);
  }
  // Warped quadrilateral: the integral of n dA over a bilinear surface is half the cross product of its diagonals,
  // and the tributary areas of a trapezoid are larger at its long side.
  const double warped[12] = {0, 0, 0, 2, 0, 0.3, 2.2, 1.5, -0.2, -0.1, 1, 0.4};
  FaceIntegrals(3, 4, warped, w, an);
  const double d1[3] = {2.2, 1.5, -0.2}, d2[3] = {-2.1, 1, 0.1};
  const double half_cross[3] = {0.5 * (d1[1] * d2[2] - d1[2] * d2[1]), 0.5 * (d1[2] * d2[0] - d1[0] * d2[2]),
                                0.5 * (d1[0] * d2[1] - d1[1] * d2[0])};
  for (int d = 0; d < 3; ++d) {
    const double sum = an[0][d] + an[1][d] + an[2][d] + an[3][d];
    EXPECT_NEAR(sum, half_cross[d], 1e-14) << "component " << d;
  }
  const double trapezoid[12] = {0, 0, 0, 4, 0, 0, 3, 1, 0, 1, 1, 0};
  FaceIntegrals(3, 4, trapezoid, w, an);
  EXPECT_NEAR(w[0] + w[1] + w[2] + w[3], 3.0, 1e-14);
  EXPECT_GT(w[0], w[3]);
  EXPECT_NEAR(w[0], w[1], 1e-15);
  // On the trapezoid x_xi x x_eta = (3 - eta) / 4, so int N_0 dA = int (1 - xi)(1 - eta)(3 - eta) / 16 = 5 / 6.
  EXPECT_NEAR(w[0], 5.0 / 6, 1e-14);
}

} // namespace
} // namespace signorini
