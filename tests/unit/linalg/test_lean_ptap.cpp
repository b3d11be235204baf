// LeanPtAPAttach: P^T A P of a parallel matrix by the ranks' sequential products equals PETSc's own product, in the
// first product and in a product reusing the result's pattern (MAT_REUSE_MATRIX, as GAMG's later set-ups). With one
// rank nothing is attached and the test compares PETSc with itself; unit_tests_run_on_root_np2 runs it on 2 ranks.
#include "signorini/core/handle.hpp"
#include "signorini/linalg/lean_ptap.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace signorini {
namespace {

/// A banded symmetric matrix of 2-dof nodes (bandwidth 7 rows: each rank's rows couple to its neighbours'), with
/// uneven row counts per rank.
PetscErrorCode BandMatrix(MPI_Comm comm, PetscMPIInt rank, Mat *A) {
  PetscFunctionBeginUser;
  const PetscInt n = 2 * (40 + 7 * rank);
  PetscCall(MatCreateAIJ(comm, n, n, PETSC_DETERMINE, PETSC_DETERMINE, 15, nullptr, 15, nullptr, A));
  PetscCall(MatSetBlockSizes(*A, 2, 2));
  PetscInt start, end, N;
  PetscCall(MatGetOwnershipRange(*A, &start, &end));
  PetscCall(MatGetSize(*A, &N, nullptr));
  for (PetscInt i = start; i < end; ++i)
    for (PetscInt j = std::max<PetscInt>(0, i - 7); j <= std::min<PetscInt>(N - 1, i + 7); ++j) {
      const PetscScalar v = i == j ? 10.0 : 1.0 / (1.0 + (double)((i + j) % 5) + std::abs((double)(i - j)));
      PetscCall(MatSetValue(*A, i, j, v, INSERT_VALUES));
    }
  PetscCall(MatAssemblyBegin(*A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*A, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/// A prolongator onto 9 coarse unknowns per rank in blocks of 3 (the near null space's vectors per node: not a
/// multiple of A's blocks of 2), each fine row with entries in four coarse columns, some on the next rank.
PetscErrorCode Prolongator(Mat A, Mat *P) {
  PetscFunctionBeginUser;
  PetscInt m, start, end, N;
  PetscCall(MatGetLocalSize(A, &m, nullptr));
  PetscCall(MatGetOwnershipRange(A, &start, &end));
  PetscCall(MatGetSize(A, &N, nullptr));
  PetscCall(
      MatCreateAIJ(PetscObjectComm((PetscObject)A), m, 9, PETSC_DETERMINE, PETSC_DETERMINE, 4, nullptr, 4, nullptr, P));
  PetscCall(MatSetBlockSizes(*P, 2, 3));
  PetscInt NC;
  PetscCall(MatGetSize(*P, nullptr, &NC));
  for (PetscInt i = start; i < end; ++i)
    for (PetscInt k = 0; k < 4; ++k) {
      const PetscInt c = (i * NC / N + 2 * k) % NC;
      PetscCall(MatSetValue(*P, i, c, 0.25 + 0.1 * (double)k + 0.01 * (double)(i % 7), ADD_VALUES));
    }
  PetscCall(MatAssemblyBegin(*P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*P, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/// ||X - Y||_F / ||Y||_F.
double RelativeDifference(Mat X, Mat Y) {
  MatH D;
  PetscReal d = -1, y = 0;
  if (MatDuplicate(X, MAT_COPY_VALUES, D.out()) || MatAXPY(D, -1.0, Y, DIFFERENT_NONZERO_PATTERN) ||
      MatNorm(D, NORM_FROBENIUS, &d) || MatNorm(Y, NORM_FROBENIUS, &y))
    return INFINITY;
  return y > 0 ? d / y : INFINITY;
}

TEST(LeanPtAP, EqualsPetscProductFirstAndReused) {
  MPI_Comm comm = PETSC_COMM_WORLD;
  PetscMPIInt rank;
  ASSERT_EQ(MPI_Comm_rank(comm, &rank), MPI_SUCCESS);
  MatH A, P, Cref, C;
  ASSERT_EQ(BandMatrix(comm, rank, A.out()), 0);
  ASSERT_EQ(Prolongator(A, P.out()), 0);
  ASSERT_EQ(MatPtAP(A, P, MAT_INITIAL_MATRIX, PETSC_DEFAULT, Cref.out()), 0);
  ASSERT_EQ(LeanPtAPAttach(A), 0);
  ASSERT_EQ(MatPtAP(A, P, MAT_INITIAL_MATRIX, PETSC_DEFAULT, C.out()), 0);
  PetscInt bs[2];
  ASSERT_EQ(MatGetBlockSizes(C, &bs[0], &bs[1]), 0);
  EXPECT_EQ(bs[0], 3);
  EXPECT_EQ(bs[1], 3);
  EXPECT_LE(RelativeDifference(C, Cref), 1e-14);
  // New values of A on the same pattern: the product into the kept result (MAT_REUSE_MATRIX) against PETSc's product
  // of a fresh matrix with the same values.
  MatH B, Bref;
  ASSERT_EQ(BandMatrix(comm, rank, B.out()), 0);
  for (Mat M : {A.get(), B.get()}) {
    ASSERT_EQ(MatShift(M, 3.0), 0);
    ASSERT_EQ(MatScale(M, 0.5), 0);
  }
  ASSERT_EQ(MatPtAP(B, P, MAT_INITIAL_MATRIX, PETSC_DEFAULT, Bref.out()), 0);
  Mat c = C;
  ASSERT_EQ(MatPtAP(A, P, MAT_REUSE_MATRIX, PETSC_DEFAULT, &c), 0);
  EXPECT_LE(RelativeDifference(C, Bref), 1e-14);
  EXPECT_GE(RelativeDifference(Cref, Bref), 1e-3); // the values did change
}

} // namespace
} // namespace signorini
