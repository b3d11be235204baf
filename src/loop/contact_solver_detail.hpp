// Shared by the files of the contact solver (contact_solver.cpp: per run and per load step; active_set_step.cpp: per
// active-set iteration; newton_step.cpp: per Newton iteration). Not installed.
#pragma once

#include "signorini/loop/contact_solver.hpp"

#include <algorithm>
#include <mpi.h>

namespace signorini::detail {

/// The smallest det F of an invertible deformation. A cell that a trial step squeezes to within round-off of zero
/// volume has a det F of about 1e-16 whose sign round-off decides, so that the same trial state could be invertible on
/// two ranks and not on one (test rank_independence:svk_degenerate_cell). It counts as non-invertible on any number
/// of ranks.
constexpr double MIN_DET_F = 1e-10;

/// Log events of the loop, registered by ContactSolver::Setup (EV_FINT: F_int from the cells, EV_PRODUCT: from K du).
extern PetscLogEvent EV_ASSEMBLY, EV_ACTIVE_SET, EV_SOLVE, EV_FINT, EV_STIFFNESS, EV_PRODUCT;

/// Accumulates the wall time of a scope (maximum over ranks is taken when reported).
class ScopedTimer {
public:
  explicit ScopedTimer(double &total) : total_(total), start_(MPI_Wtime()) {}
  ~ScopedTimer() { total_ += MPI_Wtime() - start_; }
  ScopedTimer(const ScopedTimer &) = delete;
  ScopedTimer &operator=(const ScopedTimer &) = delete;

private:
  double &total_;
  double start_;
};

inline PairIndex IndexPairs(const std::vector<ContactPair> &pairs) {
  PairIndex index;
  for (std::size_t p = 0; p < pairs.size(); ++p) index[{pairs[p].vertex, pairs[p].facet}] = p;
  return index;
}

/// Linear material: a pair's zone is fixed in the reference configuration (EvaluatePairs: inside = zone0), so a pair
/// outside it can never be active. Dropping it keeps a fine obstacle mesh (a node within the search radius of many
/// facets) from adding a multiplier, an identity row and a stabilising spring per facet.
inline void DropOutOfZone(std::vector<ContactPair> &pairs) {
  pairs.erase(std::remove_if(pairs.begin(), pairs.end(), [](const ContactPair &p) { return !p.zone0; }), pairs.end());
}

} // namespace signorini::detail
