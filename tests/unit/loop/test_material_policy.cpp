// The material models as the loop sees them (MakeMaterialPolicy): each model's answers; pure, no MPI.
#include "signorini/loop/material_policy.hpp"

#include <gtest/gtest.h>

namespace signorini {
namespace {

/// What the loop must be told about a model.
struct Expected {
  MaterialModel model;
  bool nonlinear, current_configuration;
  int cycle_repeats;
  bool pivots;
  Reason converged;
};

TEST(MaterialPolicy, EachModelsAnswers) {
  // Linear: one solve per active set on a constant K, the pairs of the reference configuration, Lemke as the last
  // resort. svk: Newton steps, the pairs of the current configuration, a set counts as cycling on its third return.
  const Expected expected[] = {
      {MaterialModel::LINEAR, false, false, 1, true, Reason::CONVERGED_ACTIVE_SET_UNCHANGED},
      {MaterialModel::SVK, true, true, 3, false, Reason::CONVERGED_ACTIVE_SET_AND_RESIDUAL},
  };
  for (const Expected &e : expected) {
    const auto m = MakeMaterialPolicy(e.model);
    EXPECT_EQ(m->Nonlinear(), e.nonlinear);
    EXPECT_EQ(m->CurrentConfiguration(), e.current_configuration);
    EXPECT_EQ(m->CycleRepeats(), e.cycle_repeats);
    EXPECT_EQ(m->Pivots(), e.pivots);
    EXPECT_EQ(m->ConvergedReason(), e.converged);
  }
}

} // namespace
} // namespace signorini
