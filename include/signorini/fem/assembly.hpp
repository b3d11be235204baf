// Global assembly of the stiffness K(u), the internal force F_int(u), the external loads and the Dirichlet data
// into the displacement rows of the saddle-point numbering.
#pragma once

#include "signorini/bc/boundary_conditions.hpp"
#include "signorini/fem/dof_map.hpp"
#include "signorini/fem/element.hpp"
#include "signorini/fem/material.hpp"
#include "signorini/mesh/mesh.hpp"

#include <functional>
#include <vector>

namespace signorini {

/// Dirichlet data per local vertex dof (v * dim + k): whether it is fixed, its full prescribed value and its ramp.
struct DirichletData {
  std::vector<char> fixed;
  std::vector<double> value;
  std::vector<int> ramp;   ///< per dof, its index in ramps (0 when it is free)
  std::vector<Ramp> ramps; ///< the distinct ramps of the -bc_dirichlet items, the proportional one first
  /// The prescribed value of dof i at the load steps' pseudo-time t: value * ramp(t) (t * value without ramps).
  [[nodiscard]] double At(std::size_t i, double t) const {
    return (ramp.empty() ? t : ramps[ramp[i]].At(t)) * value[i];
  }
};

/// Marks the Dirichlet dofs of every local vertex (ghosts included). Unknown groups are errors, and so are two items
/// prescribing different values or ramps to one node component (the message names the node, the component, both
/// values and both items, the same on any number of ranks). Collective.
[[nodiscard]] PetscErrorCode BuildDirichlet(const Mesh &mesh, const BoundaryConditions &bc, DirichletData &data);
/// Checks the groups of the loads (-bc_traction, -bc_pressure: a physical curve in 2D, a surface in 3D;
/// -bc_point_force: any group), so that a wrong name stops the run before the set-up; each error names the option and
/// its item. Collective.
[[nodiscard]] PetscErrorCode CheckLoadGroups(const Mesh &mesh, const BoundaryConditions &bc);

class Assembler {
public:
  /// The element kernels take each cell's constants: material's E and nu, or per group those AssignCellMaterials
  /// gave the cell (material.cell_constants, set before).
  Assembler(const Mesh &mesh, const Material &material, const DofMap &dofs, const DirichletData &dirichlet);

  /// Checks every local cell's Jacobian (positive, no inversion). Collective.
  [[nodiscard]] PetscErrorCode CheckCells() const;
  /// Inserts the nonzero pattern of K (free rows and columns) and the Dirichlet diagonal into A (values 0). A is the
  /// whole saddle-point matrix (DofMap::Row) or its displacement block alone (DofMap::URow), told by its size; so in
  /// Assemble.
  [[nodiscard]] PetscErrorCode InsertPattern(Mat A) const;
  /// Bounds of the nonzeros of K per owned displacement row (local row order, dofs.OwnedU() values) in the columns
  /// this rank owns (d_nnz) and in the others (o_nnz), from the cells around each vertex: exact for a vertex whose
  /// cells are all on this rank; a vertex shared with other ranks gets the sum of every rank's count of its row (an
  /// upper bound: the columns of the interface that both sides' cells hold count twice). Collective.
  [[nodiscard]] PetscErrorCode PatternCounts(std::vector<PetscInt> &d_nnz, std::vector<PetscInt> &o_nnz) const;
  /// Adds K(u) to A (free rows and columns, plus dirichlet_diag on the Dirichlet diagonal) when A is given, and
  /// F_int(u) to fint (every displacement row, Dirichlet rows included) when fint is given. u_local holds dim values
  /// per local vertex. Returns through min_J the smallest det F over the cells (svk). The force alone at u = 0 on every
  /// rank is zero: no pass over the cells then. Collective.
  [[nodiscard]] PetscErrorCode Assemble(const double *u_local, Mat A, double dirichlet_diag, Vec fint,
                                        double *min_J) const;
  /// Adds K(u) v to the free rows of f, for v nonzero on Dirichlet dofs only (the coupling of a prescribed
  /// displacement increment into the free rows). u_local, v_local: dim values per local vertex. Collective.
  [[nodiscard]] PetscErrorCode AddStiffnessTimes(const double *u_local, const double *v_local, Vec f) const;
  /// Adds the external loads (tractions, pressures, point forces, body force) at the load steps' pseudo-time t to f,
  /// each item scaled by its ramp at t (t itself without a ramp). Collective.
  [[nodiscard]] PetscErrorCode AssembleLoads(const BoundaryConditions &bc, double t, Vec f) const;
  /// Cell strain, stress and von Mises at u, handed to use(c, result) cell by cell (local cells; no array of them:
  /// at 1M cells it would take 120 MB at the peak of the output).
  [[nodiscard]] PetscErrorCode CellResults(const double *u_local,
                                           const std::function<void(PetscInt, const CellStress &)> &use) const;
  /// Mean diagonal entry of the element stiffness (a stiffness scale for Dirichlet rows) and, optionally, the mean
  /// over the global rows of sum_j |K_ij| summed element by element (the scale of the round-off of K u: abs_row_sum ||u||
  /// eps). Linear material at u = 0. Collective.
  [[nodiscard]] PetscErrorCode StiffnessScale(double &scale, double *abs_row_sum = nullptr) const;

private:
  /// Adds f_local (dim values per local vertex, ghosts included) to the displacement rows of f and assembles f.
  /// Collective.
  [[nodiscard]] PetscErrorCode AddLocal(const std::vector<double> &f_local, Vec f) const;
  /// The first row in A of each local vertex (component k: + k): DofMap::FirstRows of the whole saddle-point matrix or
  /// of its displacement block, told by A's size (InsertPattern). Not collective.
  [[nodiscard]] PetscErrorCode FirstRows(Mat A, const PetscInt *&first) const;
  /// The local cells of every local vertex: cells[first[v]] to cells[first[v + 1] - 1]. Not collective.
  void VertexCells(std::vector<PetscInt> &first, std::vector<PetscInt> &cells) const;
  bool Geometry(PetscInt c, ElementGeometry &g, PetscInt &nn, const PetscInt *&vertices) const;
  /// The index into parts_ of local cell c.
  int Part(PetscInt c) const { return material_.cell_constants.empty() ? 0 : material_.cell_constants[c]; }
  /// The elasticity matrix (Voigt) of one material.
  struct Elasticity {
    double D[6][6];
  };
  const Mesh &mesh_;
  const Material &material_;
  std::vector<Material> parts_;   ///< the run's materials: material_ alone, or one per entry of material_.constants
  std::vector<Elasticity> part_D_; ///< the elasticity matrix of each of parts_, computed once
  const DofMap &dofs_;
  const DirichletData &dirichlet_;
};

} // namespace signorini
