// The active-set policy: first set, activation with damping, parallel pairs, cycle detection, certificate.
#include "signorini/contact/active_set.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace signorini {

void DropParallelPairs(const std::vector<PairState> &states, const std::vector<PairKey> &keys,
                       const std::vector<std::array<double, 3>> &normals, double gap_tol, std::vector<char> &next) {
  const double cos_parallel = std::cos(M_PI / 180.0);
  for (std::size_t p = 0; p < keys.size(); ++p) {
    if (!next[p]) continue;
    for (std::size_t q = p + 1; q < keys.size() && keys[q].vertex == keys[p].vertex && next[p]; ++q) {
      double dot = 0;
      for (int d = 0; d < 3; ++d) dot += normals[p][d] * normals[q][d];
      if (!next[q] || dot <= cos_parallel) continue;
      // The pair the node penetrates deeper by more than gap_tol stays; within it (collinear facets have the same
      // gap), the active one, else the earlier one.
      const bool q_deeper = states[q].gap < states[p].gap - gap_tol;
      const bool tie = !q_deeper && !(states[p].gap < states[q].gap - gap_tol);
      if (q_deeper || (tie && states[q].active && !states[p].active)) next[p] = 0;
      else next[q] = 0;
    }
  }
}

void ProposeSet(const std::vector<PairState> &states, double c, double tol, double activate_tol,
                const std::vector<PairKey> &keys, const std::vector<std::array<double, 3>> &normals,
                std::vector<char> &next, double gap_tol) {
  next.resize(states.size());
  for (std::size_t p = 0; p < states.size(); ++p) next[p] = NextActive(states[p], c, tol, activate_tol);
  for (std::size_t a = 0; a < states.size();) {
    std::size_t b = a;
    while (b < states.size() && keys[b].vertex == keys[a].vertex) ++b;
    // The node's pairs are [a, b): the first crossed of its newly activated entered pairs.
    std::size_t first = b;
    for (std::size_t p = a; p < b; ++p) {
      if (!next[p] || states[p].active || !states[p].entered) continue;
      if (first == b || states[p].crossing < states[first].crossing - 1e-9 ||
          (states[p].crossing <= states[first].crossing + 1e-9 && states[p].gap < states[first].gap))
        first = p;
    }
    if (first != b)
      for (std::size_t p = a; p < b; ++p)
        if (next[p] && !states[p].active && p != first) next[p] = 0;
    a = b;
  }
  DropParallelPairs(states, keys, normals, gap_tol, next);
}

bool Certificate::Satisfied() const { return Violation().empty(); }

std::string Certificate::Violation() const {
  char text[512] = "";
  if (!(max_penetration <= gap_tol))
    std::snprintf(text, sizeof(text), "a node penetrates the obstacle by %.6g (-contact_gap_tol %.6g)", max_penetration,
                  gap_tol);
  else if (!(unpaired_penetration <= gap_tol))
    std::snprintf(text, sizeof(text),
                  "node %" PetscInt_FMT " (at %.6g, %.6g, %.6g) penetrates the obstacle by %.6g on a facet it has no contact "
                  "pair with: the facet was farther than -contact_search_radius %.6g from the node when the pairs were "
                  "found, or (linear material) its zone did not hold the node there", unpaired_node, unpaired_x[0],
                  unpaired_x[1], unpaired_x[2], unpaired_penetration, search_radius);
  else if (!(min_active_lambda >= -lambda_tol))
    std::snprintf(text, sizeof(text), "an active pair carries a tensile multiplier %.6g (tolerance %.6g)",
                  min_active_lambda, lambda_tol);
  else if (!(max_inactive_lambda <= lambda_tol))
    std::snprintf(text, sizeof(text), "an inactive pair carries a multiplier %.6g", max_inactive_lambda);
  else if (!(complementarity <= complementarity_tol))
    std::snprintf(text, sizeof(text), "complementarity max |lambda g| = %.6g exceeds %.6g", complementarity,
                  complementarity_tol);
  else if (!(equilibrium <= equilibrium_tol))
    std::snprintf(text, sizeof(text), "the equilibrium residual %.6g exceeds %.6g (-newton_rtol, -newton_atol)",
                  equilibrium, equilibrium_tol);
  else if (changes != 0)
    std::snprintf(text, sizeof(text), "the active-set rule would still switch %" PetscInt_FMT " pair(s)", changes);
  else if (bodies && !(pair_force_balance <= pair_force_tol))
    std::snprintf(text, sizeof(text), "the contact forces on the two sides of the pairs of bodies differ by %.6g "
                  "(tolerance %.6g)", pair_force_balance, pair_force_tol);
  else return friction.Violation();
  return text;
}

PetscErrorCode ActiveSet::First(const std::vector<PairState> &states, bool first_step, const std::vector<PairKey> &keys,
                                const std::vector<std::array<double, 3>> &normals, std::vector<char> &next) {
  PetscFunctionBeginUser;
  next.resize(states.size());
  start_gap_.resize(states.size());
  for (std::size_t p = 0; p < states.size(); ++p) start_gap_[p] = states[p].gap;
  started_ = true;
  half_overlap_ = false;
  if (!first_step)
    next = active_;
  else {
    double within = params_.touch_tol, deepest = 0;
    if (overlap_rule_) {
      // Candidates that start inside the obstacle (an indenter placed into the body): a smooth (locally parabolic)
      // indenter pressed to a depth d touches over r^2 = R d (Hertz) where it overlaps the body over r^2 = 2 R d, so
      // the first set is the pairs that start at least half the deepest overlap in (an overlap all at one depth, a
      // flat punch's, stays whole). The 824k-dof cube under a sphere placed 0.01 into it: 69 of the 129 overlapping
      // pairs, the answer's set, and 2 active-set iterations where the whole overlap took 4 (129, 89, 69, 69).
      for (std::size_t p = 0; p < states.size(); ++p)
        if (states[p].InZone()) deepest = std::min(deepest, states[p].gap);
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &deepest, 1, MPI_DOUBLE, MPI_MIN, comm_));
      if (OVERLAP_FRACTION * deepest < -params_.touch_tol) within = OVERLAP_FRACTION * deepest;
    }
    PetscInt count[2] = {0, 0}; // held, touching or overlapping
    for (std::size_t p = 0; p < states.size(); ++p) {
      next[p] = states[p].InZone() && states[p].gap <= within;
      count[0] += next[p], count[1] += states[p].InZone() && states[p].gap <= params_.touch_tol;
    }
    if (overlap_rule_) {
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, count, 2, MPIU_INT, MPI_SUM, comm_));
      half_overlap_ = count[0] < count[1];
      if (half_overlap_)
        PetscCall(PetscInfo(nullptr,
                            "first set: %" PetscInt_FMT " of the %" PetscInt_FMT " pairs that start touching "
                            "or overlapping, those at least %.6g in (the deepest %.6g)\n",
                            count[0], count[1], -within, -deepest));
    }
  }
  DropParallelPairs(states, keys, normals, params_.GapTol(), next);
  PetscFunctionReturn(0);
}

PetscErrorCode ActiveSet::Next(const std::vector<PairState> &states, PetscInt it, bool loose,
                               const std::vector<PairKey> &keys, const std::vector<std::array<double, 3>> &normals,
                               std::vector<char> &next, PetscInt &changes) const {
  PetscFunctionBeginUser;
  // The first update of a load step damps the overshoot after the solve with the initial (touching or previous)
  // set; later updates activate every penetrating pair, so that the last pairs are not held back. The deepest
  // penetration of an inactive pair always qualifies.
  // - Fraction: only pairs penetrating deeper than the fraction times the deepest penetration.
  // - Gap factor: only pairs whose gap at the start of the load step is at most the factor times that of the deepest
  //   pair(s) (those within 1e-9 of the deepest penetration, so that round-off does not choose among near ties).
  // An active pair stays active while its multiplier is not tensile beyond TensileTol; an inactive one is activated
  // when it penetrates beyond the gap tolerance (c gap_tol), or beyond the first update's damping.
  double local[2] = {0, 0}, global[2]; // deepest penetration of an inactive pair, largest |lambda|
  for (std::size_t p = 0; p < states.size(); ++p) {
    if (!active_[p] && states[p].InZone()) local[0] = std::max(local[0], -states[p].gap);
    local[1] = std::max(local[1], std::abs(states[p].lambda));
  }
  PetscCallMPI(MPI_Allreduce(local, global, 2, MPI_DOUBLE, MPI_MAX, comm_));
  const double gdeepest = global[0];
  // The first update after a first set of half an overlap is not damped: that solve held the body where the
  // indenter presses hardest and did not overshoot; the pairs it leaves penetrating are the ring just outside its set,
  // which the answer mostly holds. The cube under a sphere at 4.1M dofs: the gap factor held back 22 of the pairs
  // (their start gaps are negative, and the factor then admits only pairs as deep as the deepest penetrating one's
  // start), 185 -> 191 -> 221 -> 213 -> 213 pairs, now 185 -> 221 -> 213 -> 213: one active-set iteration fewer, as
  // on every depth and mesh of that cube tried at 1k-25k dofs (docs/performance.md, twenty-first session).
  const bool damped = it == 1 && !half_overlap_;
  if (it == 1 && half_overlap_)
    PetscCall(PetscInfo(nullptr, "first update after a first set of half an overlap: every penetrating pair activated "
                                 "(not damped)\n"));
  const double frac = damped ? params_.activation_fraction : 0.0;
  const double tol = TensileTol(global[1]), activate_tol = std::max(params_.ForceTol(), params_.c * frac * gdeepest);
  std::vector<PairState> current = states;
  for (std::size_t p = 0; p < states.size(); ++p) {
    current[p].active = active_[p];
    // After a loose solve an active pair's gap is its row's residual, which the solve left within its tolerance
    // (the linear material's row holds the gap at 0 in an exact solve): the rule reads its multiplier alone. With
    // lambda - c g, pairs that press on the obstacle were released because their gap had opened by the solve's
    // error (the 16k-dof octant: 2 of 4 switches; 5 active-set iterations where exact solves take 3).
    if (loose && active_[p]) current[p].gap = 0;
  }
  ProposeSet(current, params_.c, tol, activate_tol, keys, normals, next, params_.GapTol());
  // Only with the start gaps of the current pairs (First since the last Reset): a flag every rank sets alike, not the
  // sizes, which agree trivially on a rank without pairs after a Reset and made the ranks' collectives below differ.
  if (damped && params_.activation_gap_factor > 0 && started_ && gdeepest > 0) {
    double g = -INFINITY, G;
    for (std::size_t p = 0; p < states.size(); ++p)
      if (!active_[p] && states[p].InZone() && -states[p].gap >= (1 - 1e-9) * gdeepest) g = std::max(g, start_gap_[p]);
    PetscCallMPI(MPI_Allreduce(&g, &G, 1, MPI_DOUBLE, MPI_MAX, comm_));
    const double limit = std::max(G, params_.activation_gap_factor * G);
    PetscInt held = 0;
    for (std::size_t p = 0; p < states.size(); ++p)
      if (next[p] && !active_[p] && start_gap_[p] > limit) next[p] = 0, ++held;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &held, 1, MPIU_INT, MPI_SUM, comm_));
    PetscCall(PetscInfo(nullptr, "first update: %" PetscInt_FMT " penetrating pair(s) held back (gap at the start of "
                        "the step above %.6g)\n", held, limit));
  }
  if (single_) PetscCall(KeepOneSwitch(current, keys, next));
  PetscInt mine = 0;
  for (std::size_t p = 0; p < states.size(); ++p) mine += next[p] != active_[p];
  PetscCallMPI(MPI_Allreduce(&mine, &changes, 1, MPIU_INT, MPI_SUM, comm_));
  PetscFunctionReturn(0);
}

PetscErrorCode ActiveSet::KeepOneSwitch(const std::vector<PairState> &states, const std::vector<PairKey> &keys,
                                        std::vector<char> &next) const {
  PetscFunctionBeginUser;
  const auto score = [&](std::size_t p) { return std::abs(states[p].lambda - params_.c * states[p].gap); };
  double best = -1;
  for (std::size_t p = 0; p < next.size(); ++p)
    if (next[p] != active_[p]) best = std::max(best, score(p));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &best, 1, MPI_DOUBLE, MPI_MAX, comm_));
  // The smallest (node, facet) among the pairs that reach the largest score: node first, then facet.
  int64_t key[2] = {INT64_MAX, INT64_MAX};
  for (int k = 0; k < 2; ++k) {
    int64_t mine = INT64_MAX;
    for (std::size_t p = 0; p < next.size(); ++p)
      if (next[p] != active_[p] && score(p) == best && (k == 0 || keys[p].original == key[0]))
        mine = std::min<int64_t>(mine, k == 0 ? keys[p].original : keys[p].facet);
    PetscCallMPI(MPI_Allreduce(&mine, &key[k], 1, MPI_INT64_T, MPI_MIN, comm_));
  }
  for (std::size_t p = 0; p < next.size(); ++p) {
    if (next[p] == active_[p]) continue;
    if (keys[p].original != key[0] || keys[p].facet != key[1]) next[p] = active_[p];
    else
      PetscCall(PetscInfo(nullptr, "one switch: node %" PetscInt_FMT " facet %" PetscInt_FMT " %s (lambda %.6g, gap "
                          "%.6g)\n", keys[p].original, keys[p].facet, next[p] ? "activated" : "released",
                          states[p].lambda, states[p].gap));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ActiveSet::SwitchOneAtATime(const std::vector<PairState> &states, const std::vector<PairKey> &keys,
                                           std::vector<char> &next, PetscInt &changes) {
  PetscFunctionBeginUser;
  single_ = true;
  seen_.clear();
  std::vector<PairState> current = states;
  for (std::size_t p = 0; p < states.size(); ++p) current[p].active = active_[p];
  PetscCall(KeepOneSwitch(current, keys, next));
  PetscInt mine = 0;
  for (std::size_t p = 0; p < next.size(); ++p) mine += next[p] != active_[p];
  PetscCallMPI(MPI_Allreduce(&mine, &changes, 1, MPIU_INT, MPI_SUM, comm_));
  PetscFunctionReturn(0);
}

PetscErrorCode ActiveSet::Seen(const std::vector<char> &next, const std::vector<PairKey> &keys, int repeats,
                               bool &cycling, bool record) {
  // An order-independent hash of the set (a sum of mixed keys), the same on every partition.
  unsigned long long mine = 0, h;
  PetscFunctionBeginUser;
  for (std::size_t p = 0; p < keys.size(); ++p)
    if (next[p]) {
      // A flag above 1 (friction's stick and slip sets, Friction::SetKey) is another state of the pair.
      unsigned long long z = (unsigned long long)keys[p].original * 1000003ULL + (unsigned long long)keys[p].facet +
                             0x9E3779B97F4A7C15ULL + (unsigned long long)(next[p] - 1) * 0x632BE59BD9B4E019ULL;
      z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
      z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
      mine += z ^ (z >> 31);
    }
  PetscCallMPI(MPI_Allreduce(&mine, &h, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, comm_));
  cycling = std::count(seen_.begin(), seen_.end(), h) >= repeats;
  if (record) seen_.push_back(h);
  PetscFunctionReturn(0);
}

PetscErrorCode ActiveSet::Certify(const std::vector<PairState> &states, const std::vector<PairKey> &keys,
                                  const std::vector<std::array<double, 3>> &normals, double equilibrium,
                                  double equilibrium_tol, Certificate &cert) const {
  // Local maxima: penetration, -min active lambda, max |inactive lambda|, max |lambda g|, max lambda, max |lambda|.
  double m[6] = {0, -INFINITY, 0, 0, 0, 0}, g[6];
  PetscInt counts[2] = {0, 0}, gcounts[2];
  PetscFunctionBeginUser;
  std::vector<char> next;
  for (std::size_t p = 0; p < states.size(); ++p) {
    const PairState &s = states[p];
    if (s.InZone()) m[0] = std::max(m[0], -s.gap);
    if (s.active) m[1] = std::max(m[1], -s.lambda), counts[1]++;
    else m[2] = std::max(m[2], std::abs(s.lambda));
    m[3] = std::max(m[3], std::abs(s.lambda * s.gap));
    m[4] = std::max(m[4], s.lambda);
    m[5] = std::max(m[5], std::abs(s.lambda));
  }
  PetscCallMPI(MPI_Allreduce(m, g, 6, MPI_DOUBLE, MPI_MAX, comm_));
  const double tensile_tol = TensileTol(g[5]);
  ProposeSet(states, params_.c, tensile_tol, params_.ForceTol(), keys, normals, next, params_.GapTol());
  for (std::size_t p = 0; p < states.size(); ++p) counts[0] += next[p] != (char)states[p].active;
  PetscCallMPI(MPI_Allreduce(counts, gcounts, 2, MPIU_INT, MPI_SUM, comm_));
  cert.max_penetration = std::max(0.0, g[0]);
  cert.gap_tol = params_.GapTol();
  cert.min_active_lambda = gcounts[1] ? -g[1] : 0.0;
  cert.lambda_tol = tensile_tol;
  cert.max_inactive_lambda = g[2];
  cert.complementarity = g[3];
  cert.complementarity_tol = params_.GapTol() * std::max(g[4], cert.lambda_tol);
  cert.equilibrium = equilibrium;
  cert.equilibrium_tol = equilibrium_tol;
  cert.changes = gcounts[0];
  cert.active = gcounts[1];
  PetscFunctionReturn(0);
}

} // namespace signorini
