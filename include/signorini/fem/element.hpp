// Reference elements (P1 triangle and tetrahedron, Q1 quadrilateral and hexahedron, the linear pyramid), quadrature,
// and the element kernels: linear small-strain elasticity and St. Venant-Kirchhoff with Green-Lagrange strain, in 2D
// and 3D.
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

/// Fills the geometry of a cell with `nodes` vertices (3 triangle, 4 quadrilateral in 2D; 4 tetrahedron, 5 pyramid,
/// 8 hexahedron in 3D) at coordinates X (dim values per vertex, in gmsh's order: cyclic in 2D, the hexahedron's top
/// face above its bottom face, the pyramid's base counter-clockwise seen from its apex, the apex last). Returns false
/// for an unknown cell.
bool ComputeGeometry(int dim, int nodes, const double *X, double thickness, ElementGeometry &g);

/// Element stiffness (tangent, Eq. 17) and internal force (Eq. 15 without contact and loads) at the element
/// displacement u (dim values per vertex). For the linear model K does not depend on u and f = K u.
/// K is (nodes*dim)^2 row-major, f has nodes*dim entries; both are overwritten. K may be null (the force alone).
/// Returns the smallest det F = det(I + grad u) over the quadrature points (svk; 1 for the linear model).
double ElementTangentAndForce(const Material &m, const ElementGeometry &g, const double *u, double *K, double *f);
/// The same with the material's elasticity matrix D (Voigt, ElasticityMatrix) computed once by the caller.
double ElementTangentAndForce(const Material &m, const double (&D)[6][6], const ElementGeometry &g, const double *u,
                              double *K, double *f);
/// The isotropic elasticity matrix in Voigt form (engineering shear strain; 2D: plane strain or stress).
void ElasticityMatrix(const Material &m, int dim, double D[6][6]);

/// Strain and stress averaged over the cell, in Voigt order (xx, yy, xy) in 2D and (xx, yy, zz, yz, xz, xy) in 3D,
/// with tensor (not engineering) shear strain; 2D outputs also sigma_zz. Linear: small strain and Cauchy stress;
/// svk: Green-Lagrange strain and Cauchy stress sigma = F S F^T / J. Returns the minimum J over the quadrature points.
struct CellStress {
  std::array<double, 6> strain{}, stress{};
  double strain_zz = 0, stress_zz = 0, von_mises = 0, min_J = 1; ///< *_zz: the out-of-plane components in 2D
};
CellStress ElementStress(const Material &m, const ElementGeometry &g, const double *u);

/// Smallest det F = det(I + grad u) over the quadrature points at the element displacement u.
double MinDeformationJacobian(const ElementGeometry &g, const double *u);

/// Consistent nodal integrals over a boundary face with n vertices at X (dim values each, oriented as Face in
/// mesh.hpp: an edge in 2D, a triangle or a bilinear quadrilateral in 3D): w[a] = int N_a dA and an[a] = int N_a n dA
/// with n the unit outward normal (3 values per vertex). A uniform traction t gives the nodal forces w[a] t, a
/// pressure p the forces -p an[a]; w is also the tributary length or area of a node.
void FaceIntegrals(int dim, int n, const double *X, double *w, double (*an)[3]);

/// Body force contribution t * int N_a b dA (b per unit volume).
void ElementBodyForce(const ElementGeometry &g, const double *b, double *f);

} // namespace signorini
