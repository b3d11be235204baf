// Element kernels: symmetry, rigid modes and rank of the stiffness, patch tests, plane strain/stress constants,
// and the St. Venant-Kirchhoff tangent, small-strain limit and frame indifference.
#include "signorini/fem/element.hpp"

#include "fem/element_test_util.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
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

struct Cell {
  std::string name;
  int nodes;
  Vector X; ///< 2 coordinates per vertex, counter-clockwise
};

const Cell TRIANGLE{"triangle", 3, {0.1, 0.2, 1.3, 0.4, 0.5, 1.6}};
const Cell SQUARE{"square", 4, {0, 0, 1, 0, 1, 1, 0, 1}};
const Cell DISTORTED_QUAD{"distorted quad", 4, {0, 0, 2, 0.3, 1.6, 1.4, -0.2, 1.1}};
const Cell CELLS[] = {TRIANGLE, SQUARE, DISTORTED_QUAD};

Material MakeMaterial(bool plane_stress, MaterialModel model = MaterialModel::LINEAR) {
  Material m;
  m.E = 200.0;
  m.nu = 0.3;
  m.plane_stress = plane_stress;
  m.model = model;
  return m;
}

std::string Describe(const Cell &cell, const Material &m) {
  return cell.name + (m.plane_stress ? ", plane stress" : ", plane strain") + ", " + m.ModelName();
}

ElementGeometry Geometry(const Cell &cell, double thickness = 1.0) {
  ElementGeometry g;
  EXPECT_TRUE(ComputeGeometry(2, cell.nodes, cell.X.data(), thickness, g));
  return g;
}

/// Element stiffness and force at displacement u.
void TangentAndForce(const Material &m, const Cell &cell, const Vector &u, Vector &K, Vector &f,
                     double thickness = 1.0) {
  const int n = 2 * cell.nodes;
  K.assign(n * n, 0.0);
  f.assign(n, 0.0);
  const ElementGeometry g = Geometry(cell, thickness);
  ElementTangentAndForce(m, g, u.data(), K.data(), f.data());
}

Vector Stiffness(const Material &m, const Cell &cell, double thickness = 1.0) {
  Vector K, f;
  TangentAndForce(m, cell, Vector(2 * cell.nodes, 0.0), K, f, thickness);
  return K;
}

Vector Force(const Material &m, const Cell &cell, const Vector &u) {
  Vector K, f;
  TangentAndForce(m, cell, u, K, f);
  return f;
}

double Area(const Cell &cell) {
  double a = 0;
  for (int k = 0; k < cell.nodes; ++k) {
    const int l = (k + 1) % cell.nodes;
    a += cell.X[2 * k] * cell.X[2 * l + 1] - cell.X[2 * l] * cell.X[2 * k + 1];
  }
  return 0.5 * a;
}

/// Nodal values of the displacement u(x) = a + B x.
Vector LinearField(const Vector &X, const double a[2], const double B[2][2]) {
  Vector u(X.size());
  for (std::size_t k = 0; k < X.size() / 2; ++k)
    for (int i = 0; i < 2; ++i)
      u[2 * k + i] = a[i] + B[i][0] * X[2 * k] + B[i][1] * X[2 * k + 1];
  return u;
}

/// The three rigid-body modes of the linear theory: x and y translations, infinitesimal rotation about the origin.
std::vector<Vector> RigidModes(const Vector &X) {
  const std::size_t n = X.size();
  std::vector<Vector> modes(3, Vector(n, 0.0));
  for (std::size_t k = 0; k < n / 2; ++k) {
    modes[0][2 * k] = 1.0;
    modes[1][2 * k + 1] = 1.0;
    modes[2][2 * k] = -X[2 * k + 1];
    modes[2][2 * k + 1] = X[2 * k];
  }
  return modes;
}

/// Hand formulas: in-plane Cauchy stress (xx, yy, xy) and sigma_zz of the linear law for a small strain.
void HookeStress(const Material &m, const double eps[3], double sigma[3], double &sigma_zz) {
  const double E = m.E, nu = m.nu;
  if (m.plane_stress) {
    const double c = E / (1 - nu * nu);
    sigma[0] = c * (eps[0] + nu * eps[1]);
    sigma[1] = c * (eps[1] + nu * eps[0]);
    sigma_zz = 0;
  } else {
    const double c = E / ((1 + nu) * (1 - 2 * nu));
    sigma[0] = c * ((1 - nu) * eps[0] + nu * eps[1]);
    sigma[1] = c * ((1 - nu) * eps[1] + nu * eps[0]);
    sigma_zz = c * nu * (eps[0] + eps[1]);
  }
  sigma[2] = E / (1 + nu) * eps[2];
}

double VonMises(double sx, double sy, double sz, double txy) {
  return std::sqrt(0.5 * ((sx - sy) * (sx - sy) + (sy - sz) * (sy - sz) + (sz - sx) * (sz - sx)) + 3 * txy * txy);
}

TEST(ElementGeometry, WeightsSumToAreaTimesThicknessAndUnknownCellsAreRejected) {
  for (const Cell &cell : CELLS) {
    SCOPED_TRACE(cell.name);
    const ElementGeometry g = Geometry(cell, 2.5);
    double sum = 0;
    for (int q = 0; q < g.nqp; ++q)
      sum += g.w[q];
    EXPECT_NEAR(sum, 2.5 * Area(cell), 1e-13 * Area(cell));
    EXPECT_GT(g.min_detJ, 0.0);
    // Partition of unity of the shape functions and zero sum of their gradients at every quadrature point.
    for (int q = 0; q < g.nqp; ++q) {
      double N = 0, dx = 0, dy = 0;
      for (int a = 0; a < g.nodes; ++a)
        N += g.N[q][a], dx += g.dN[q][a][0], dy += g.dN[q][a][1];
      EXPECT_NEAR(N, 1.0, 1e-14);
      EXPECT_NEAR(dx, 0.0, 1e-13);
      EXPECT_NEAR(dy, 0.0, 1e-13);
    }
  }
  ElementGeometry g;
  const double pentagon[10] = {0, 0, 1, 0, 1.5, 1, 0.5, 1.5, -0.5, 1};
  EXPECT_FALSE(ComputeGeometry(2, 5, pentagon, 1.0, g));
}

TEST(LinearElement, StiffnessIsSymmetric) {
  for (bool plane_stress : {false, true})
    for (const Cell &cell : CELLS) {
      const Material m = MakeMaterial(plane_stress);
      SCOPED_TRACE(Describe(cell, m));
      const Vector K = Stiffness(m, cell);
      const int n = 2 * cell.nodes;
      double asym = 0;
      for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c)
          asym = std::max(asym, std::abs(K[r * n + c] - K[c * n + r]));
      EXPECT_LE(asym, 1e-12 * MaxAbs(K));
      EXPECT_GT(MaxAbs(K), 0.0);
    }
}

TEST(LinearElement, RigidModesAreInTheNullSpace) {
  for (bool plane_stress : {false, true})
    for (const Cell &cell : CELLS) {
      const Material m = MakeMaterial(plane_stress);
      SCOPED_TRACE(Describe(cell, m));
      const Vector K = Stiffness(m, cell);
      const auto modes = RigidModes(cell.X);
      for (std::size_t k = 0; k < modes.size(); ++k) {
        SCOPED_TRACE("rigid mode " + std::to_string(k));
        EXPECT_LE(Norm(MatVec(K, modes[k])), 1e-12 * Norm(K) * Norm(modes[k]));
      }
    }
}

TEST(LinearElement, ExactlyThreeZeroEigenvaluesAndTheRestPositive) {
  for (bool plane_stress : {false, true})
    for (const Cell &cell : CELLS) {
      const Material m = MakeMaterial(plane_stress);
      SCOPED_TRACE(Describe(cell, m));
      const int n = 2 * cell.nodes;
      const Vector eig = SymmetricEigenvalues(Stiffness(m, cell), n);
      const double largest = eig.back();
      ASSERT_GT(largest, 0.0);
      for (int i = 0; i < 3; ++i)
        EXPECT_LE(std::abs(eig[i]), 1e-12 * largest) << "eigenvalue " << i;
      for (int i = 3; i < n; ++i)
        EXPECT_GT(eig[i], 1e-4 * largest) << "eigenvalue " << i;
    }
}

TEST(LinearElement, PatchTestGivesExactConstantStrainAndStress) {
  const double a[2] = {0.3, -0.2}, B[2][2] = {{1.0e-3, 2.0e-3}, {-0.5e-3, 3.0e-3}};
  const double eps[3] = {B[0][0], B[1][1], 0.5 * (B[0][1] + B[1][0])};
  for (bool plane_stress : {false, true})
    for (const Cell &cell : CELLS) {
      const Material m = MakeMaterial(plane_stress);
      SCOPED_TRACE(Describe(cell, m));
      double sigma[3], sigma_zz;
      HookeStress(m, eps, sigma, sigma_zz);
      const Vector u = LinearField(cell.X, a, B);
      const CellStress s = ElementStress(m, Geometry(cell), u.data());
      const double eps_scale = 1e-10 * MaxAbs(Vector(eps, eps + 3));
      const double sigma_scale = 1e-10 * MaxAbs(Vector(sigma, sigma + 3));
      for (int v = 0; v < 3; ++v) {
        EXPECT_NEAR(s.strain[v], eps[v], eps_scale) << "strain component " << v;
        EXPECT_NEAR(s.stress[v], sigma[v], sigma_scale) << "stress component " << v;
      }
      EXPECT_NEAR(s.stress_zz, sigma_zz, sigma_scale);
      EXPECT_NEAR(s.von_mises, VonMises(sigma[0], sigma[1], sigma_zz, sigma[2]), sigma_scale);
    }
}

/// A 3x3 patch on [0,3]^2 with four distorted interior nodes, alternating quadrilaterals and pairs of triangles.
struct Patch {
  Vector X;
  std::vector<std::vector<int>> cells;
  std::vector<int> interior;
};

Patch MakePatch() {
  Patch p;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i)
      p.X.insert(p.X.end(), {(double)i, (double)j});
  const int interior[4] = {5, 6, 9, 10};
  const double moved[4][2] = {{1.2, 0.9}, {2.1, 1.25}, {0.85, 2.1}, {1.9, 1.8}};
  for (int k = 0; k < 4; ++k) {
    p.X[2 * interior[k]] = moved[k][0];
    p.X[2 * interior[k] + 1] = moved[k][1];
    p.interior.push_back(interior[k]);
  }
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const int n0 = 4 * j + i, n1 = n0 + 1, n2 = n0 + 5, n3 = n0 + 4;
      if ((i + j) % 2 == 0) {
        p.cells.push_back({n0, n1, n2, n3});
      } else {
        p.cells.push_back({n0, n1, n2});
        p.cells.push_back({n0, n2, n3});
      }
    }
  return p;
}

/// Internal force of the patch assembled by hand.
Vector AssemblePatchForce(const Material &m, const Patch &p, const Vector &u) {
  Vector f(p.X.size(), 0.0);
  for (const auto &nodes : p.cells) {
    Cell cell{"patch cell", (int)nodes.size(), {}};
    Vector ue;
    for (int v : nodes) {
      cell.X.insert(cell.X.end(), {p.X[2 * v], p.X[2 * v + 1]});
      ue.insert(ue.end(), {u[2 * v], u[2 * v + 1]});
    }
    EXPECT_GT(Area(cell), 0.0);
    const Vector fe = Force(m, cell, ue);
    for (std::size_t k = 0; k < nodes.size(); ++k)
      for (int i = 0; i < 2; ++i)
        f[2 * nodes[k] + i] += fe[2 * k + i];
  }
  return f;
}

/// Strain energy density times 2 (eps^T D eps) of a small strain (xx, yy, tensor xy) in the plane.
double TwiceEnergyDensity(const Material &m, const double eps[3]) {
  double sigma[3], sigma_zz;
  HookeStress(m, eps, sigma, sigma_zz);
  return sigma[0] * eps[0] + sigma[1] * eps[1] + 2 * sigma[2] * eps[2];
}

TEST(LinearElement, EnergyOfALinearFieldIsExact) {
  const double a[2] = {0, 0}, B[2][2] = {{1.0e-3, 2.0e-3}, {-0.5e-3, 3.0e-3}};
  const double eps[3] = {B[0][0], B[1][1], 0.5 * (B[0][1] + B[1][0])};
  for (bool plane_stress : {false, true})
    for (const Cell &cell : CELLS) {
      const Material m = MakeMaterial(plane_stress);
      SCOPED_TRACE(Describe(cell, m));
      const Vector u = LinearField(cell.X, a, B), Ku = MatVec(Stiffness(m, cell, 1.5), u);
      double uKu = 0;
      for (std::size_t i = 0; i < u.size(); ++i)
        uKu += u[i] * Ku[i];
      const double expected = 1.5 * Area(cell) * TwiceEnergyDensity(m, eps);
      EXPECT_NEAR(uKu, expected, 1e-12 * expected);
    }
}

TEST(LinearElement, SquareBendingModeEnergyIsExact) {
  // u_x = alpha (2x - 1)(2y - 1) on the unit square: eps_xx = 2 alpha (2y - 1), 2 eps_xy = 2 alpha (2x - 1);
  // u^T K u = (D_11 + mu) 4 alpha^2 / 3 when the quadratic integrand is integrated exactly.
  const double alpha = 1e-3;
  Vector u(8, 0.0);
  for (int k = 0; k < 4; ++k)
    u[2 * k] = alpha * (2 * SQUARE.X[2 * k] - 1) * (2 * SQUARE.X[2 * k + 1] - 1);
  for (bool plane_stress : {false, true}) {
    const Material m = MakeMaterial(plane_stress);
    SCOPED_TRACE(Describe(SQUARE, m));
    const double D11 = plane_stress ? m.E / (1 - m.nu * m.nu) : m.E * (1 - m.nu) / ((1 + m.nu) * (1 - 2 * m.nu));
    const Vector Ku = MatVec(Stiffness(m, SQUARE), u);
    double uKu = 0;
    for (std::size_t i = 0; i < u.size(); ++i)
      uKu += u[i] * Ku[i];
    const double expected = (D11 + m.Mu()) * 4 * alpha * alpha / 3;
    EXPECT_NEAR(uKu, expected, 1e-12 * expected);
  }
}

TEST(LinearElement, TriangleIsTheConstantStrainTriangle) {
  // K = t A B^T D B with B from the edge vectors: dN_i/dx = (y_j - y_k) / 2A, dN_i/dy = (x_k - x_j) / 2A.
  const Vector &X = TRIANGLE.X;
  const double A = Area(TRIANGLE), t = 0.7;
  double Bm[3][6] = {};
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    const double bx = (X[2 * j + 1] - X[2 * k + 1]) / (2 * A), by = (X[2 * k] - X[2 * j]) / (2 * A);
    Bm[0][2 * i] = bx;
    Bm[1][2 * i + 1] = by;
    Bm[2][2 * i] = by;
    Bm[2][2 * i + 1] = bx;
  }
  for (bool plane_stress : {false, true}) {
    const Material m = MakeMaterial(plane_stress);
    SCOPED_TRACE(Describe(TRIANGLE, m));
    const double D11 = plane_stress ? m.E / (1 - m.nu * m.nu) : m.E * (1 - m.nu) / ((1 + m.nu) * (1 - 2 * m.nu));
    const double D12 = plane_stress ? m.nu * D11 : m.nu / (1 - m.nu) * D11;
    const double D[3][3] = {{D11, D12, 0}, {D12, D11, 0}, {0, 0, m.Mu()}};
    Vector expected(36, 0.0);
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c)
        for (int v = 0; v < 3; ++v)
          for (int w = 0; w < 3; ++w)
            expected[r * 6 + c] += t * A * Bm[v][r] * D[v][w] * Bm[w][c];
    EXPECT_LE(MaxAbs(Difference(Stiffness(m, TRIANGLE, t), expected)), 1e-12 * MaxAbs(expected));
  }
}

TEST(LinearElement, PatchTestInteriorForcesCancel) {
  const Patch patch = MakePatch();
  const double a[2] = {0.3, -0.2}, B[2][2] = {{1.0e-3, 2.0e-3}, {-0.5e-3, 3.0e-3}};
  const Vector u = LinearField(patch.X, a, B);
  for (bool plane_stress : {false, true}) {
    const Material m = MakeMaterial(plane_stress);
    SCOPED_TRACE(m.plane_stress ? "plane stress" : "plane strain");
    const Vector f = AssemblePatchForce(m, patch, u);
    const double scale = MaxAbs(f);
    ASSERT_GT(scale, 0.0);
    for (int v : patch.interior) {
      EXPECT_NEAR(f[2 * v], 0.0, 1e-10 * scale) << "interior node " << v;
      EXPECT_NEAR(f[2 * v + 1], 0.0, 1e-10 * scale) << "interior node " << v;
    }
  }
}

TEST(LinearElement, StiffnessScalesLinearlyWithThickness) {
  for (const Cell &cell : CELLS) {
    const Material m = MakeMaterial(false);
    SCOPED_TRACE(Describe(cell, m));
    const Vector K1 = Stiffness(m, cell, 1.0), K3 = Stiffness(m, cell, 2.5);
    Vector scaled(K1);
    for (double &k : scaled)
      k *= 2.5;
    EXPECT_LE(MaxAbs(Difference(K3, scaled)), 1e-12 * MaxAbs(scaled));
  }
}

TEST(LinearElement, PlaneStrainAndPlaneStressConstants) {
  const double e = 1e-3;
  const Cell &cell = DISTORTED_QUAD;
  const double a[2] = {0, 0}, uniaxial_strain[2][2] = {{e, 0}, {0, 0}};
  const Vector u = LinearField(cell.X, a, uniaxial_strain);

  Material strain = MakeMaterial(false);
  const double E = strain.E, nu = strain.nu;
  const CellStress s1 = ElementStress(strain, Geometry(cell), u.data());
  const double c = E / ((1 + nu) * (1 - 2 * nu));
  EXPECT_NEAR(s1.stress[0], c * (1 - nu) * e, 1e-10 * E * e);
  EXPECT_NEAR(s1.stress[1], c * nu * e, 1e-10 * E * e);
  EXPECT_NEAR(s1.stress[2], 0.0, 1e-10 * E * e);
  EXPECT_NEAR(s1.stress_zz, c * nu * e, 1e-10 * E * e);
  EXPECT_EQ(s1.strain_zz, 0.0);

  Material stress = MakeMaterial(true);
  const CellStress s2 = ElementStress(stress, Geometry(cell), u.data());
  EXPECT_NEAR(s2.stress[0], E / (1 - nu * nu) * e, 1e-10 * E * e);
  EXPECT_NEAR(s2.stress[1], E * nu / (1 - nu * nu) * e, 1e-10 * E * e);
  EXPECT_NEAR(s2.stress_zz, 0.0, 1e-10 * E * e);

  // Uniaxial stress in plane stress: eps_yy = -nu eps_xx leaves sigma_yy = 0 and sigma_xx = E eps_xx.
  const double uniaxial_stress[2][2] = {{e, 0}, {0, -nu * e}};
  const Vector w = LinearField(cell.X, a, uniaxial_stress);
  const CellStress s3 = ElementStress(stress, Geometry(cell), w.data());
  EXPECT_NEAR(s3.stress[0], E * e, 1e-10 * E * e);
  EXPECT_NEAR(s3.stress[1], 0.0, 1e-10 * E * e);
  EXPECT_NEAR(s3.von_mises, E * e, 1e-10 * E * e);
  EXPECT_NEAR(s3.strain_zz, -nu * e, 1e-12 * e); // sigma_zz = 0 with the 3D law: eps_zz = -nu sigma_xx / E
}

TEST(LinearElement, ForceIsStiffnessTimesDisplacement) {
  Random random;
  for (const Cell &cell : CELLS) {
    const Material m = MakeMaterial(false);
    SCOPED_TRACE(Describe(cell, m));
    Vector u(2 * cell.nodes), K, f;
    for (double &x : u)
      x = 0.1 * random.Next();
    TangentAndForce(m, cell, u, K, f);
    EXPECT_LE(Norm(Difference(f, MatVec(K, u))), 1e-12 * Norm(K) * Norm(u));
    EXPECT_LE(Norm(Difference(K, Stiffness(m, cell))), 1e-14 * Norm(K)); // K does not depend on u
  }
}

TEST(LinearElement, BodyForceDistributesTheTotalLoad) {
  const double b[2] = {0.5, -2.0};
  for (const Cell &cell : CELLS) {
    SCOPED_TRACE(cell.name);
    const ElementGeometry g = Geometry(cell, 3.0);
    Vector f(2 * cell.nodes, -1.0);
    ElementBodyForce(g, b, f.data());
    double total[2] = {0, 0};
    for (int k = 0; k < cell.nodes; ++k)
      total[0] += f[2 * k], total[1] += f[2 * k + 1];
    for (int i = 0; i < 2; ++i)
      EXPECT_NEAR(total[i], b[i] * Area(cell) * 3.0, 1e-13 * Area(cell) * 6.0);
    if (cell.nodes == 3) {
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(f[2 * k + 1], b[1] * Area(cell), 1e-13 * Area(cell) * 6.0);
    }
  }
}

/// Random displacement of amplitude 0.1 times the element size.
Vector RandomDisplacement(const Cell &cell, Random &random) {
  const double h = std::sqrt(Area(cell));
  Vector u(2 * cell.nodes);
  for (double &x : u)
    x = 0.1 * h * random.Next();
  return u;
}

TEST(SvkElement, TangentMatchesCentralFiniteDifferenceOfTheForce) {
  Random random;
  for (bool plane_stress : {false, true})
    for (const Cell &cell : {TRIANGLE, DISTORTED_QUAD}) {
      const Material m = MakeMaterial(plane_stress, MaterialModel::SVK);
      SCOPED_TRACE(Describe(cell, m));
      const int n = 2 * cell.nodes;
      const Vector u = RandomDisplacement(cell, random);
      ASSERT_GT(ElementStress(m, Geometry(cell), u.data()).min_J, 0.5);
      Vector K, f;
      TangentAndForce(m, cell, u, K, f);
      const double h = 1e-6 * std::sqrt(Area(cell));
      const Vector K_fd = test::CentralDifferenceJacobian(u, h, [&](const Vector &v) { return Force(m, cell, v); });
      EXPECT_LE(Norm(Difference(K, K_fd)), 1e-6 * Norm(K));
      // The state is genuinely nonlinear: the tangent differs from the linear stiffness.
      EXPECT_GT(Norm(Difference(K, Stiffness(MakeMaterial(plane_stress), cell))), 1e-2 * Norm(K));
      // The tangent of a hyperelastic law is symmetric.
      EXPECT_LE(test::MaxAsymmetry(K, n), 1e-12 * MaxAbs(K));
    }
}

TEST(Element, ForceAloneEqualsTheForceComputedWithTheTangent) {
  Random random;
  for (MaterialModel model : {MaterialModel::LINEAR, MaterialModel::SVK})
    for (const Cell &cell : {TRIANGLE, DISTORTED_QUAD}) {
      const Material m = MakeMaterial(false, model);
      SCOPED_TRACE(Describe(cell, m));
      const Vector u = RandomDisplacement(cell, random);
      Vector K, f, f_alone(2 * cell.nodes, 1e300);
      TangentAndForce(m, cell, u, K, f);
      ElementTangentAndForce(m, Geometry(cell), u.data(), nullptr, f_alone.data());
      EXPECT_EQ(f_alone, f);
    }
}

TEST(SvkElement, ReducesToLinearForSmallDisplacements) {
  Random random;
  const double epsilon = 1e-7;
  for (bool plane_stress : {false, true})
    for (const Cell &cell : CELLS) {
      const Material svk = MakeMaterial(plane_stress, MaterialModel::SVK), linear = MakeMaterial(plane_stress);
      SCOPED_TRACE(Describe(cell, svk));
      const Vector u = RandomDisplacement(cell, random);
      Vector small(u);
      for (double &x : small)
        x *= epsilon;
      Vector f_svk = Force(svk, cell, small);
      for (double &x : f_svk)
        x /= epsilon;
      const Vector f_lin = Force(linear, cell, u);
      EXPECT_LE(Norm(Difference(f_svk, f_lin)), 1e-6 * Norm(f_lin));
      // At u = 0 the svk tangent is the linear stiffness.
      const Vector K_lin = Stiffness(linear, cell), K_svk = Stiffness(svk, cell);
      EXPECT_LE(Norm(Difference(K_svk, K_lin)), 1e-12 * Norm(K_lin));
    }
}

TEST(SvkElement, FiniteRigidRotationIsStressFree) {
  const double theta = M_PI / 6, c = std::cos(theta), s = std::sin(theta);
  const double a[2] = {0.4, -0.7}, R_minus_I[2][2] = {{c - 1, -s}, {s, c - 1}};
  for (bool plane_stress : {false, true})
    for (const Cell &cell : CELLS) {
      const Material svk = MakeMaterial(plane_stress, MaterialModel::SVK), linear = MakeMaterial(plane_stress);
      SCOPED_TRACE(Describe(cell, svk));
      const Vector u = LinearField(cell.X, a, R_minus_I);
      const double scale = Norm(Stiffness(linear, cell)) * Norm(u);
      EXPECT_LE(Norm(Force(svk, cell, u)), 1e-12 * scale);
      EXPECT_GT(Norm(Force(linear, cell, u)), 1e-2 * scale);
      const CellStress st = ElementStress(svk, Geometry(cell), u.data());
      for (int v = 0; v < 3; ++v) {
        EXPECT_NEAR(st.strain[v], 0.0, 1e-14) << "component " << v;
        EXPECT_NEAR(st.stress[v], 0.0, 1e-12 * svk.E) << "component " << v;
      }
      EXPECT_NEAR(st.min_J, 1.0, 1e-14);
    }
}

TEST(SvkElement, UniaxialStretchGivesGreenLagrangeStrainAndCauchyStress) {
  const double stretch = 1.2, a[2] = {0.1, 0.2}, B[2][2] = {{stretch - 1, 0}, {0, 0}};
  const double E_xx = 0.5 * (stretch * stretch - 1);
  for (bool plane_stress : {false, true})
    for (const Cell &cell : CELLS) {
      const Material m = MakeMaterial(plane_stress, MaterialModel::SVK);
      SCOPED_TRACE(Describe(cell, m));
      const double lambda = m.plane_stress ? 2 * m.Lambda3D() * m.Mu() / (m.Lambda3D() + 2 * m.Mu()) : m.Lambda3D();
      const double S_xx = (lambda + 2 * m.Mu()) * E_xx, S_yy = lambda * E_xx;
      const Vector u = LinearField(cell.X, a, B);
      const CellStress st = ElementStress(m, Geometry(cell), u.data());
      const double tol = 1e-10 * m.E;
      EXPECT_NEAR(st.strain[0], E_xx, 1e-12);
      EXPECT_NEAR(st.strain[1], 0.0, 1e-12);
      EXPECT_NEAR(st.strain[2], 0.0, 1e-12);
      // sigma = F S F^T / J with F = diag(stretch, 1), J = stretch.
      EXPECT_NEAR(st.stress[0], stretch * S_xx, tol);
      EXPECT_NEAR(st.stress[1], S_yy / stretch, tol);
      EXPECT_NEAR(st.stress[2], 0.0, tol);
      EXPECT_NEAR(st.stress_zz, m.plane_stress ? 0.0 : m.Lambda3D() * E_xx / stretch, tol);
      EXPECT_NEAR(st.min_J, stretch, 1e-13);
    }
}

TEST(SvkElement, PatchTestInteriorForcesCancelForAHomogeneousDeformation) {
  const Patch patch = MakePatch();
  const double a[2] = {0.3, -0.2}, B[2][2] = {{0.15, 0.1}, {-0.05, -0.12}};
  const Vector u = LinearField(patch.X, a, B);
  for (bool plane_stress : {false, true}) {
    const Material m = MakeMaterial(plane_stress, MaterialModel::SVK);
    SCOPED_TRACE(m.plane_stress ? "plane stress" : "plane strain");
    const Vector f = AssemblePatchForce(m, patch, u);
    const double scale = MaxAbs(f);
    ASSERT_GT(scale, 0.0);
    for (int v : patch.interior) {
      EXPECT_NEAR(f[2 * v], 0.0, 1e-10 * scale) << "interior node " << v;
      EXPECT_NEAR(f[2 * v + 1], 0.0, 1e-10 * scale) << "interior node " << v;
    }
  }
}

} // namespace
} // namespace signorini
