// The material models as the contact loop sees them (material_policy.hpp): linear elasticity and St. Venant-Kirchhoff.
#include "signorini/loop/material_policy.hpp"

namespace signorini {

namespace {

/// Linear small-strain elasticity: a constant K, the pairs of the reference configuration.
class LinearPolicy final : public MaterialPolicy {
public:
  bool Nonlinear() const override { return false; }
  bool CurrentConfiguration() const override { return false; }
  int CycleRepeats() const override { return 1; }
  bool Pivots() const override { return true; }
  Reason ConvergedReason() const override { return Reason::CONVERGED_ACTIVE_SET_UNCHANGED; }
};

/// St. Venant-Kirchhoff (Green-Lagrange strain): Newton steps, the pairs of the current configuration.
class SvkPolicy final : public MaterialPolicy {
public:
  bool Nonlinear() const override { return true; }
  bool CurrentConfiguration() const override { return true; }
  int CycleRepeats() const override { return 3; }
  bool Pivots() const override { return false; }
  Reason ConvergedReason() const override { return Reason::CONVERGED_ACTIVE_SET_AND_RESIDUAL; }
};

} // namespace

std::unique_ptr<const MaterialPolicy> MakeMaterialPolicy(MaterialModel model) {
  switch (model) {
  case MaterialModel::SVK:
    return std::make_unique<SvkPolicy>();
  case MaterialModel::LINEAR:
    break;
  }
  return std::make_unique<LinearPolicy>();
}

} // namespace signorini
