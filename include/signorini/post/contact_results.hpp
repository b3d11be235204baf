// Contact results: per-node multiplier, pressure, gap and active flag, and the global quantities of the summary
// (contact force and its balance, contact length, peak pressure, penetration, complementarity residual).
#pragma once

#include "signorini/fem/material.hpp"
#include "signorini/loop/solved_state.hpp"

#include <array>
#include <vector>

namespace signorini {

struct ContactSummary {
  PetscInt candidates = 0, pairs = 0, active_pairs = 0, active_nodes = 0;
  std::array<double, 3> contact_force{}, applied_force{}, reaction_force{};
  /// Pairs of bodies (-contact_pairs): the contact force on their master sides (contact_force holds the slave sides'
  /// and the obstacles'); equal and opposite to the slave sides' to round-off
  std::array<double, 3> master_force{};
  bool bodies = false; ///< the case has pairs of bodies
  /// Friction (-contact_friction > 0): the friction force on the body (its part of contact_force, which holds the
  /// whole force of the obstacles: normal and friction).
  bool friction = false;
  std::array<double, 3> friction_force{};
  double force_balance = 0;   ///< |contact + master + applied + reaction| / max(|applied|, |contact|)
  double contact_length = 0;  ///< sum of tributary lengths of the active nodes
  double max_pressure = 0, max_penetration = 0, complementarity = 0, min_lambda = 0;
  double max_displacement = 0, strain_energy = 0;
};

/// Per local vertex: summed multiplier, pressure lambda / (w t), smallest gap over its pairs in their zone (NaN
/// where there is none), active flag.
struct NodeContact {
  std::vector<double> lambda, pressure, gap, active;
  /// With friction, per local vertex: the friction force on the body and its traction (force / (w t)), dim values
  /// each, the slip of the last load step (dim values), and the set: 0 open, 1 slip, 2 stick.
  std::vector<double> friction, friction_traction, slip, friction_state;
};

/// The per-node contact fields and the summary's global quantities of a solved state. Collective.
[[nodiscard]] PetscErrorCode ComputeContactResults(const SolvedState &state, const Material &material,
                                                   NodeContact &nodes, ContactSummary &summary);

} // namespace signorini
