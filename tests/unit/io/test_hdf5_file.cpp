// The HDF5 file written by every rank together: datasets of rows x cols, each rank its slab, read back with HDF5's
// own serial reader; a failure on one rank is a failure on every rank.
#include "signorini/io/hdf5_file.hpp"

#include "io/shared_path.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <cstdio>
#include <string>
#include <type_traits>
#include <vector>

namespace signorini {
namespace {

/// The dimensions and the values of a dataset of a file, read on this rank alone.
template <typename T> std::vector<T> ReadDataset(const std::string &path, const char *name, std::vector<hsize_t> &dims) {
  std::vector<T> values;
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t set = file >= 0 ? H5Dopen2(file, name, H5P_DEFAULT) : -1;
  if (set >= 0) {
    const hid_t space = H5Dget_space(set);
    dims.assign(H5Sget_simple_extent_ndims(space), 0);
    H5Sget_simple_extent_dims(space, dims.data(), nullptr);
    values.resize(H5Sget_simple_extent_npoints(space));
    H5Dread(set, std::is_same<T, double>::value ? H5T_NATIVE_DOUBLE : H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT,
            values.data());
    H5Sclose(space);
    H5Dclose(set);
  }
  if (file >= 0) H5Fclose(file);
  return values;
}

TEST(Hdf5File, EachRankWritesItsSlabOfRowsInOrder) {
  PetscMPIInt rank, size;
  ASSERT_EQ(MPI_Comm_rank(PETSC_COMM_WORLD, &rank), MPI_SUCCESS);
  ASSERT_EQ(MPI_Comm_size(PETSC_COMM_WORLD, &size), MPI_SUCCESS);
  const std::string path = test::SharedTempPath("hdf5_file.h5");
  // Rank r holds r rows, the last rank r + 2: on two ranks rank 0 has none and takes part in each write with an empty
  // selection.
  const long long mine = rank == size - 1 ? rank + 2 : rank;
  long long first = 0, rows = 0;
  ASSERT_EQ(MPI_Exscan(&mine, &first, 1, MPI_LONG_LONG, MPI_SUM, PETSC_COMM_WORLD), MPI_SUCCESS);
  ASSERT_EQ(MPI_Allreduce(&mine, &rows, 1, MPI_LONG_LONG, MPI_SUM, PETSC_COMM_WORLD), MPI_SUCCESS);
  if (rank == 0) first = 0; // MPI_Exscan leaves rank 0's result undefined
  std::vector<double> xyz;
  std::vector<long long> tags;
  for (long long k = first; k < first + mine; ++k) {
    for (int c = 0; c < 3; ++c) xyz.push_back(10.0 * k + c + 0.5);
    tags.push_back(1000 + k);
  }
  Hdf5File file;
  ASSERT_EQ(file.Open(PETSC_COMM_WORLD, path, true), 0);
  ASSERT_EQ(file.CreateGroup("/mesh"), 0);
  ASSERT_EQ(file.WriteRows("/mesh/coordinates", rows, 3, first, xyz), 0);
  ASSERT_EQ(file.WriteRows("/mesh/node_tags", rows, 1, first, tags), 0);
  ASSERT_EQ(file.Close(), 0);
  EXPECT_TRUE(file.Ok()) << file.Reason();
  EXPECT_EQ(file.Path(), path);
  ASSERT_EQ(MPI_Barrier(PETSC_COMM_WORLD), MPI_SUCCESS);
  if (rank != 0) return;
  std::vector<hsize_t> dims;
  const std::vector<double> all_xyz = ReadDataset<double>(path, "/mesh/coordinates", dims);
  EXPECT_EQ(dims, (std::vector<hsize_t>{(hsize_t)rows, 3}));
  std::vector<double> expected_xyz;
  std::vector<long long> expected_tags;
  for (long long k = 0; k < rows; ++k) {
    for (int c = 0; c < 3; ++c) expected_xyz.push_back(10.0 * k + c + 0.5);
    expected_tags.push_back(1000 + k);
  }
  EXPECT_EQ(all_xyz, expected_xyz);
  // One column: a dataset of one dimension.
  EXPECT_EQ(ReadDataset<long long>(path, "/mesh/node_tags", dims), expected_tags);
  EXPECT_EQ(dims, (std::vector<hsize_t>{(hsize_t)rows}));
  std::remove(path.c_str());
}

TEST(Hdf5File, AFailureIsSharedByEveryRankAndLaterCallsDoNothing) {
  PetscMPIInt rank;
  ASSERT_EQ(MPI_Comm_rank(PETSC_COMM_WORLD, &rank), MPI_SUCCESS);
  const std::string path = test::SharedTempPath("hdf5_file_failure.h5");
  {
    Hdf5File missing;
    ASSERT_EQ(missing.Open(PETSC_COMM_WORLD, path + ".absent", false), 0); // the caller raises the error, not Open
    EXPECT_FALSE(missing.Ok());
    EXPECT_FALSE(missing.Reason().empty());
    ASSERT_EQ(missing.CreateGroup("/mesh"), 0);
    ASSERT_EQ(missing.WriteRows("/mesh/x", 1, 1, 0, std::vector<double>{1}), 0);
    EXPECT_FALSE(missing.Ok());
  }
  Hdf5File file;
  ASSERT_EQ(file.Open(PETSC_COMM_WORLD, path, true), 0);
  ASSERT_TRUE(file.Ok()) << file.Reason();
  // A dataset in a group that does not exist fails on every rank; the next dataset is not written.
  ASSERT_EQ(file.WriteRows("/absent/x", 1, 1, 0, std::vector<double>{}), 0);
  EXPECT_FALSE(file.Ok());
  EXPECT_FALSE(file.Reason().empty()) << "HDF5's reason of the failed creation";
  ASSERT_EQ(file.CreateGroup("/mesh"), 0);
  ASSERT_EQ(file.Close(), 0);
  EXPECT_FALSE(file.Ok());
  ASSERT_EQ(MPI_Barrier(PETSC_COMM_WORLD), MPI_SUCCESS);
  if (rank != 0) return;
  const hid_t h = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(h, 0);
  EXPECT_LE(H5Lexists(h, "/mesh", H5P_DEFAULT), 0) << "a group created after the failure";
  H5Fclose(h);
  std::remove(path.c_str());
}

} // namespace
} // namespace signorini
