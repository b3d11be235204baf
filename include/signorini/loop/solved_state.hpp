// A plain view of the loop's final state, for post-processing and output: what was solved, not the solver.
#pragma once

#include "signorini/contact/active_set.hpp"
#include "signorini/contact/contact_set.hpp"
#include "signorini/contact/friction.hpp"
#include "signorini/contact/mortar.hpp"
#include "signorini/fem/assembly.hpp"
#include "signorini/fem/dof_map.hpp"
#include "signorini/loop/solve_stats.hpp"
#include "signorini/mesh/mesh.hpp"

#include <petscvec.h>

#include <array>
#include <vector>

namespace signorini {

/// The converged state of a run (ContactSolver::State): references into the solver, valid while it lives.
struct SolvedState {
  const Mesh &mesh;
  const DofMap &dofs;
  const DirichletData &dirichlet;
  const std::vector<ContactPair> &pairs;
  const std::vector<PairState> &states;               ///< gap, multiplier and active flag per pair
  const std::vector<std::array<double, 3>> &normals;  ///< per pair
  const std::vector<char> &candidates;                ///< per local vertex: a candidate contact node
  const std::vector<double> &u_local;                 ///< displacement, dim values per local vertex
  Vec fext, fint; ///< external load and internal force (displacement rows of the saddle-point layout)
  const SolveStats &stats;
  const Certificate &certificate;
  const MortarCoupling *mortar; ///< the master terms of the pairs of bodies (forces on the master nodes)
  const Friction *friction;     ///< the friction at the pairs (null: frictionless)
};

} // namespace signorini
