// Global assembly on the conforming mesh of tetrahedra, pyramids and hexahedra (meshes/cube_mixed_conforming.msh):
// the patch test of the whole mesh through the mesh reader, the assembly and a direct solve.
#include "signorini/fem/assembly.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

namespace signorini {
namespace {

/// u(x) = a + B x, with a general (non-symmetric) B: stretches, shears and a rotation.
void LinearField(const double *x, double scale, double *u) {
  const double a[3] = {0.3, -0.2, 0.1};
  const double B[3][3] = {{0.15, 0.1, -0.05}, {-0.05, -0.12, 0.08}, {0.06, 0.04, 0.1}};
  for (int i = 0; i < 3; ++i)
    u[i] = scale * (a[i] + B[i][0] * x[0] + B[i][1] * x[1] + B[i][2] * x[2]);
}

class ConformingMixedMesh : public ::testing::Test {
protected:
  void SetUp() override {
    MeshOptions opts;
    opts.file = SIGNORINI_SOURCE_DIR "/meshes/cube_mixed_conforming.msh";
    ASSERT_EQ(mesh_.Create(PETSC_COMM_SELF, opts), 0);
    ASSERT_EQ(dofs_.Create(mesh_, 0), 0);
    // Every boundary dof prescribed to the linear field.
    std::vector<PetscInt> boundary;
    ASSERT_EQ(mesh_.BoundaryVertices(boundary), 0);
    const PetscInt nv = mesh_.NumLocalVertices();
    dirichlet_.fixed.assign(3 * nv, 0);
    dirichlet_.value.assign(3 * nv, 0.0);
    for (PetscInt v : boundary) {
      LinearField(mesh_.X(v), 1e-3, &dirichlet_.value[3 * v]);
      std::fill_n(&dirichlet_.fixed[3 * v], 3, 1);
    }
    // The interior holds vertices of every kind of cell, the pyramids' apexes and the shared face's inside.
    std::vector<char> on_boundary(nv, 0);
    for (PetscInt v : boundary)
      on_boundary[v] = 1;
    for (PetscInt c = 0; c < mesh_.NumLocalCells(); ++c) {
      PetscInt n;
      const PetscInt *cv = mesh_.CellVertices(c, n);
      for (PetscInt a = 0; a < n; ++a)
        if (!on_boundary[cv[a]]) interior_of_[n]++;
    }
  }

  Mesh mesh_;
  DofMap dofs_;
  DirichletData dirichlet_;
  std::map<PetscInt, int> interior_of_; ///< interior vertex slots of the cells with 4, 5 and 8 vertices
};

TEST_F(ConformingMixedMesh, ALinearFieldImposedOnTheBoundaryIsReproducedInside) {
  ASSERT_EQ(interior_of_.size(), 3u);
  Material m;
  m.E = 200;
  m.nu = 0.3;
  const Assembler assembler(mesh_, m, dofs_, dirichlet_);
  ASSERT_EQ(assembler.CheckCells(), 0);
  const PetscInt n = dofs_.OwnedRows(), nv = mesh_.NumLocalVertices();
  std::vector<PetscInt> d_nnz, o_nnz;
  ASSERT_EQ(assembler.PatternCounts(d_nnz, o_nnz), 0);
  Mat K;
  ASSERT_EQ(MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, 0, d_nnz.data(), &K), 0);
  ASSERT_EQ(MatSetOption(K, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), 0);
  const std::vector<double> zero(3 * nv, 0.0);
  ASSERT_EQ(assembler.Assemble(zero.data(), K, 1.0, nullptr, nullptr), 0);
  ASSERT_EQ(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY), 0);
  ASSERT_EQ(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY), 0);
  // K u = b with b = -K_FD u_D on the free rows and u_D on the Dirichlet rows (unit diagonal).
  Vec b, x;
  ASSERT_EQ(MatCreateVecs(K, &x, &b), 0);
  ASSERT_EQ(assembler.AddStiffnessTimes(zero.data(), dirichlet_.value.data(), b), 0);
  ASSERT_EQ(VecAssemblyBegin(b), 0);
  ASSERT_EQ(VecAssemblyEnd(b), 0);
  ASSERT_EQ(VecScale(b, -1.0), 0);
  for (PetscInt v = 0; v < nv; ++v)
    for (int k = 0; k < 3; ++k)
      if (dirichlet_.fixed[3 * v + k]) {
        ASSERT_EQ(VecSetValue(b, dofs_.Row(v, k), dirichlet_.value[3 * v + k], INSERT_VALUES), 0);
      }
  ASSERT_EQ(VecAssemblyBegin(b), 0);
  ASSERT_EQ(VecAssemblyEnd(b), 0);
  KSP ksp;
  PC pc;
  ASSERT_EQ(KSPCreate(PETSC_COMM_SELF, &ksp), 0);
  ASSERT_EQ(KSPSetOperators(ksp, K, K), 0);
  ASSERT_EQ(KSPSetType(ksp, KSPPREONLY), 0);
  ASSERT_EQ(KSPGetPC(ksp, &pc), 0);
  ASSERT_EQ(PCSetType(pc, PCLU), 0);
  ASSERT_EQ(KSPSolve(ksp, b, x), 0);
  const PetscScalar *xa;
  ASSERT_EQ(VecGetArrayRead(x, &xa), 0);
  double err = 0, size = 0;
  for (PetscInt v = 0; v < nv; ++v) {
    double u[3];
    LinearField(mesh_.X(v), 1e-3, u);
    for (int k = 0; k < 3; ++k) {
      err = std::max(err, std::abs(PetscRealPart(xa[dofs_.Row(v, k)]) - u[k]));
      size = std::max(size, std::abs(u[k]));
    }
  }
  ASSERT_EQ(VecRestoreArrayRead(x, &xa), 0);
  // Exact up to the round-off of a direct solve (the measured error is about 1e-16 of the field).
  EXPECT_LE(err, 1e-12 * size);
  ASSERT_EQ(KSPDestroy(&ksp), 0);
  ASSERT_EQ(VecDestroy(&b), 0);
  ASSERT_EQ(VecDestroy(&x), 0);
  ASSERT_EQ(MatDestroy(&K), 0);
}

TEST_F(ConformingMixedMesh, HomogeneousFiniteDeformationIsInEquilibriumForSvk) {
  // A homogeneous deformation F = I + B (|B| ~ 0.15) has a uniform second Piola-Kirchhoff stress: the internal
  // forces of the cells around an interior node cancel exactly when the cells are conforming.
  Material m;
  m.E = 200;
  m.nu = 0.3;
  m.model = MaterialModel::SVK;
  const Assembler assembler(mesh_, m, dofs_, dirichlet_);
  const PetscInt nv = mesh_.NumLocalVertices();
  std::vector<double> u(3 * nv);
  for (PetscInt v = 0; v < nv; ++v)
    LinearField(mesh_.X(v), 1.0, &u[3 * v]);
  Vec f;
  ASSERT_EQ(VecCreateSeq(PETSC_COMM_SELF, dofs_.OwnedRows(), &f), 0);
  double min_J = 0;
  ASSERT_EQ(assembler.Assemble(u.data(), nullptr, 0.0, f, &min_J), 0);
  EXPECT_GT(min_J, 0.5);
  const PetscScalar *fa;
  ASSERT_EQ(VecGetArrayRead(f, &fa), 0);
  double interior = 0, scale = 0;
  for (PetscInt v = 0; v < nv; ++v)
    for (int k = 0; k < 3; ++k) {
      const double value = std::abs(PetscRealPart(fa[dofs_.Row(v, k)]));
      scale = std::max(scale, value);
      if (!dirichlet_.fixed[3 * v + k]) interior = std::max(interior, value);
    }
  ASSERT_EQ(VecRestoreArrayRead(f, &fa), 0);
  ASSERT_GT(scale, 0.0);
  EXPECT_LE(interior, 1e-12 * scale);
  ASSERT_EQ(VecDestroy(&f), 0);
}

} // namespace
} // namespace signorini
