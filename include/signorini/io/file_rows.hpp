// Rows of per-vertex or per-cell data moved between the ranks that hold them and contiguous blocks of the file's order
// (BlockOf: one block per rank), so that each rank writes one contiguous slab of a table in the file's order.
#pragma once

#include "signorini/core/handle.hpp"

#include <vector>

namespace signorini {

class FileRows {
public:
  /// Collective. This rank contributes nrows rows: row i is entry local[i] of the arrays it will pass (i when local is
  /// empty) and row file[i] of the table of n rows; every file row must come from exactly one rank. The blocks are
  /// BlockOf(n).
  [[nodiscard]] PetscErrorCode Create(MPI_Comm comm, PetscInt n, const std::vector<PetscInt> &local,
                                      const std::vector<PetscInt> &file);
  /// First file row and number of rows of this rank's block.
  PetscInt Start() const { return start_; }
  PetscInt Size() const { return size_; }
  PetscInt Global() const { return n_; }
  /// Moves rows of ncomp values from the contributing arrays (values: ncomp per local entry) into this rank's block
  /// (block: ncomp per row of the block, in file order). Collective.
  template <typename T>
  [[nodiscard]] PetscErrorCode ToBlocks(const std::vector<T> &values, int ncomp, std::vector<T> &block) const;
  /// The reverse: the rows of the blocks back to the contributing entries (values: ncomp per local entry, sized to hold
  /// them; other entries untouched). Collective.
  template <typename T>
  [[nodiscard]] PetscErrorCode FromBlocks(const std::vector<T> &block, int ncomp, std::vector<T> &values) const;

private:
  SFH sf_;
  PetscInt start_ = 0, size_ = 0, n_ = 0, leaf_extent_ = 0;
};

} // namespace signorini
