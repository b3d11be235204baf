// Reference elements (P1 triangle, Q1 quadrilateral), quadrature, and the element kernels: linear small-strain
// elasticity and St. Venant-Kirchhoff with Green-Lagrange strain. Written for any dimension; 2D cells today.
#pragma once

#include "signorini/fem/material.hpp"

#include <array>
#include <vector>

namespace signorini {

constexpr int MAX_DIM = 3;
constexpr int MAX_NODES = 8;
constexpr int MAX_QP = 8;
constexpr int MAX_EDOF = MAX_DIM * MAX_NODES;

/// Shape functions and their physical gradients at the quadrature points of one cell.
struct ElementGeometry {
  int dim = 2, nodes = 0, nqp = 0;
  std::array<std::array<double, MAX_NODES>, MAX_QP> N{};
  std::array<std::array<std::array<double, MAX_DIM>, MAX_NODES>, MAX_QP> dN{}; ///< dN[q][a][i] = dN_a/dX_i
  std::array<double, MAX_QP> w{};  ///< quadrature weight times |det J| times thickness (2D)
  double min_detJ = 0, max_detJ = 0;
};

/// Fills the geometry of a cell with `nodes` vertices (3 triangle, 4 quadrilateral in 2D) at coordinates X
/// (dim values per vertex, vertices in cyclic order). Returns false for an unknown cell.
bool ComputeGeometry(int dim, int nodes, const double *X, double thickness, ElementGeometry &g);

/// Element stiffness (tangent, Eq. 17) and internal force (Eq. 15 without contact and loads) at the element
/// displacement u (dim values per vertex). For the linear model K does not depend on u and f = K u.
/// K is (nodes*dim)^2 row-major, f has nodes*dim entries; both are overwritten.
void ElementTangentAndForce(const Material &m, const ElementGeometry &g, const double *u, double *K, double *f);

/// Strain and stress averaged over the cell, in Voigt order (xx, yy, xy) in 2D and (xx, yy, zz, yz, xz, xy) in 3D,
/// with tensor (not engineering) shear strain; 2D outputs also sigma_zz. Linear: small strain and Cauchy stress;
/// svk: Green-Lagrange strain and Cauchy stress sigma = F S F^T / J. Returns the minimum J over the quadrature points.
struct CellStress {
  std::array<double, 6> strain{}, stress{};
  double stress_zz = 0, von_mises = 0, min_J = 1;
};
CellStress ElementStress(const Material &m, const ElementGeometry &g, const double *u);

/// Body force contribution t * int N_a b dA (b per unit volume).
void ElementBodyForce(const ElementGeometry &g, const double *b, double *f);

} // namespace signorini
