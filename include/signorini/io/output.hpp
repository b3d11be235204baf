// Output (prefix -output_): HDF5 + XDMF for ParaView (one step per load step), the per-node CSV table keyed by
// the mesh file's node tags, and summary.json. Everything is written into DIR/incomplete/ and moved into DIR only
// when the run succeeds, so a failed run never leaves files that look complete nor replaces a good earlier output.
#pragma once

#include "signorini/mesh/mesh.hpp"

#include <petscsys.h>

#include <string>
#include <vector>

namespace signorini {

struct OutputOptions {
  std::string dir; ///< -output_dir: where to write (default: nothing is written)
};

[[nodiscard]] PetscErrorCode ReadOutputOptions(MPI_Comm comm, OutputOptions &opts);

/// A field on the vertices or the cells, ncomp values per local vertex (cell), named as in the HDF5 file.
struct Field {
  std::string name;
  int ncomp = 1;
  bool on_cells = false;
  std::vector<double> values;
};

/// Gathers a per-local-vertex (or per-local-cell) array to rank 0 in the file's order (owned vertices only).
/// Collective; the result is filled on rank 0.
[[nodiscard]] PetscErrorCode GatherToRoot(const Mesh &mesh, const Field &field, std::vector<double> &out);

class OutputWriter {
public:
  /// Prepares DIR/incomplete (removing a stale one); checks that DIR can be written. Collective.
  [[nodiscard]] PetscErrorCode Open(const Mesh &mesh, const OutputOptions &opts);
  bool Enabled() const { return !opts_.dir.empty(); }
  /// Writes the fields of one load step (load factor t) and rewrites the XDMF. Collective.
  [[nodiscard]] PetscErrorCode WriteStep(PetscInt step, double t, const std::vector<Field> &fields);
  /// Writes the node table (vertex fields: name, ncomp) of the final state. Collective.
  [[nodiscard]] PetscErrorCode WriteNodeTable(const std::vector<Field> &fields);
  /// Writes summary.json (its text is given) and moves everything into DIR. Collective.
  [[nodiscard]] PetscErrorCode Publish(const std::string &summary_json);
  /// Path of the staging directory (for messages).
  std::string Staging() const { return opts_.dir + "/incomplete"; }

private:
  [[nodiscard]] PetscErrorCode WriteXdmf() const;
  /// Gathers every field to rank 0 in file order; returns this rank's number. Collective.
  [[nodiscard]] PetscErrorCode GatherFields(const std::vector<Field> &fields,
                                            std::vector<std::vector<double>> &gathered, PetscMPIInt &rank) const;
  const Mesh *mesh_ = nullptr;
  OutputOptions opts_;
  struct StepInfo {
    PetscInt step;
    double t;
    std::vector<Field> layout; // names and sizes only
  };
  std::vector<StepInfo> steps_;
  std::vector<std::string> files_;
};

} // namespace signorini
