// The text file written by every rank together: the ranks' pieces concatenated in rank order, replacing the file.
#include "signorini/io/ordered_text.hpp"

#include "io/shared_path.hpp"
#include "petsc_helpers.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

namespace signorini {
namespace {

std::string ReadFile(const std::string &path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

/// Rank r's piece: r lines (none on rank 0), each naming its rank, so that the pieces differ in length.
std::string Piece(int rank) {
  std::string text;
  for (int k = 0; k < rank; ++k) text += "rank " + std::to_string(rank) + " line " + std::to_string(k) + "\n";
  return text;
}

TEST(WriteInRankOrder, ConcatenatesThePiecesInRankOrderAndReplacesALongerFile) {
  PetscMPIInt rank, size;
  ASSERT_EQ(MPI_Comm_rank(PETSC_COMM_WORLD, &rank), MPI_SUCCESS);
  ASSERT_EQ(MPI_Comm_size(PETSC_COMM_WORLD, &size), MPI_SUCCESS);
  const std::string path = test::SharedTempPath("ordered_text.csv");
  // A longer file at the path first: what is written replaces it, no tail of it stays.
  if (rank == 0) std::ofstream(path) << std::string(10000, 'x');
  ASSERT_EQ(MPI_Barrier(PETSC_COMM_WORLD), MPI_SUCCESS);
  const std::string header = rank == 0 ? "node_tag,x\n" : "";
  ASSERT_EQ(WriteInRankOrder(PETSC_COMM_WORLD, path, header + Piece(rank + 1)), 0);
  std::string expected = "node_tag,x\n";
  for (int r = 0; r < size; ++r) expected += Piece(r + 1);
  EXPECT_EQ(ReadFile(path), expected);
  // Nothing from any rank: an empty file.
  ASSERT_EQ(WriteInRankOrder(PETSC_COMM_WORLD, path, ""), 0);
  EXPECT_EQ(ReadFile(path), "");
  ASSERT_EQ(MPI_Barrier(PETSC_COMM_WORLD), MPI_SUCCESS);
  if (rank == 0) std::remove(path.c_str());
}

TEST(WriteInRankOrder, AFileThatCannotBeWrittenIsOneErrorNamingIt) {
  const std::string path = test::SharedTempPath("no_such_directory") + "/nodes.csv";
  test::ErrorCapture capture;
  EXPECT_NE(WriteInRankOrder(PETSC_COMM_WORLD, path, "text\n"), 0);
  EXPECT_NE(capture.Message().find("cannot write '" + path + "'"), std::string::npos) << capture.Message();
}

} // namespace
} // namespace signorini
