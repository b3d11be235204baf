// Rows moved between the ranks that hold them and the blocks of the file's order, and back.
#include "signorini/io/file_rows.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace signorini {
namespace {

/// The value of component c of file row k: what every test writes and expects, whichever rank holds the row.
double Value(PetscInt k, int c) { return 100.0 * k + c; }

TEST(FileRows, OneRankPermutesItsRowsIntoTheFilesOrderAndBack) {
  FileRows rows;
  // Row i of the arrays is file row file[i].
  const std::vector<PetscInt> file = {2, 0, 3, 1};
  ASSERT_EQ(rows.Create(PETSC_COMM_SELF, 4, {}, file), 0);
  EXPECT_EQ(rows.Start(), 0);
  EXPECT_EQ(rows.Size(), 4);
  EXPECT_EQ(rows.Global(), 4);
  const std::vector<double> values = {20, 21, 0, 1, 30, 31, 10, 11};
  std::vector<double> block;
  ASSERT_EQ(rows.ToBlocks(values, 2, block), 0);
  EXPECT_EQ(block, (std::vector<double>{0, 1, 10, 11, 20, 21, 30, 31}));
  std::vector<double> back(values.size(), -1);
  ASSERT_EQ(rows.FromBlocks(block, 2, back), 0);
  EXPECT_EQ(back, values);
  // Integers (node tags) travel the same way.
  std::vector<long long> tags;
  ASSERT_EQ(rows.ToBlocks(std::vector<long long>{7, 5, 8, 6}, 1, tags), 0);
  EXPECT_EQ(tags, (std::vector<long long>{5, 6, 7, 8}));
}

TEST(FileRows, RowsFromChosenEntriesLeaveTheOthersUntouched) {
  FileRows rows;
  // Entries 4 and 1 of the arrays are file rows 0 and 1; entries 0, 2 and 3 are not rows (e.g. ghost vertices).
  ASSERT_EQ(rows.Create(PETSC_COMM_SELF, 2, {4, 1}, {0, 1}), 0);
  std::vector<double> block;
  ASSERT_EQ(rows.ToBlocks(std::vector<double>{-1, 11, -1, -1, 10}, 1, block), 0);
  EXPECT_EQ(block, (std::vector<double>{10, 11}));
  std::vector<double> values(5, -7);
  ASSERT_EQ(rows.FromBlocks(std::vector<double>{20, 21}, 1, values), 0);
  EXPECT_EQ(values, (std::vector<double>{-7, 21, -7, -7, 20}));
}

TEST(FileRows, EveryRankGetsItsContiguousBlockWhoeverHeldTheRows) {
  PetscMPIInt rank, size;
  ASSERT_EQ(MPI_Comm_rank(PETSC_COMM_WORLD, &rank), MPI_SUCCESS);
  ASSERT_EQ(MPI_Comm_size(PETSC_COMM_WORLD, &size), MPI_SUCCESS);
  // 3 rows per rank, dealt round-robin backwards: rank r holds the file rows n - 1 - r, n - 1 - r - size, ...
  const PetscInt n = 3 * size + 1;
  std::vector<PetscInt> file;
  for (PetscInt k = n - 1 - rank; k >= 0; k -= size) file.push_back(k);
  FileRows rows;
  ASSERT_EQ(rows.Create(PETSC_COMM_WORLD, n, {}, file), 0);
  std::vector<double> values;
  for (PetscInt k : file)
    for (int c = 0; c < 3; ++c) values.push_back(Value(k, c));
  std::vector<double> block;
  ASSERT_EQ(rows.ToBlocks(values, 3, block), 0);
  // The blocks tile 0 .. n-1 in rank order.
  PetscInt own = rows.Size(), start = 0, total = 0;
  ASSERT_EQ(MPI_Exscan(&own, &start, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD), MPI_SUCCESS);
  ASSERT_EQ(MPI_Allreduce(&own, &total, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD), MPI_SUCCESS);
  EXPECT_EQ(rows.Start(), rank == 0 ? 0 : start);
  EXPECT_EQ(total, n);
  ASSERT_EQ((PetscInt)block.size(), 3 * rows.Size());
  for (PetscInt j = 0; j < rows.Size(); ++j)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(block[3 * j + c], Value(rows.Start() + j, c)) << "file row " << j;
  std::vector<double> back;
  ASSERT_EQ(rows.FromBlocks(block, 3, back), 0);
  EXPECT_EQ(back, values);
}

} // namespace
} // namespace signorini
