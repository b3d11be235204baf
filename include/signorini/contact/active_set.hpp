// The active-set rule (seed section 4.2.5) written as the primal-dual complementarity test: with the sign
// convention g >= 0, lambda >= 0, lambda g = 0, a pair is active when lambda - c g > 0.
#pragma once

namespace signorini {

/// State of one pair after a solve.
struct PairState {
  double lambda = 0;   ///< multiplier (normal contact force, >= 0 compressive)
  double gap = 0;      ///< current gap (< 0 penetration)
  bool inside = false; ///< the node projects onto the facet (0 <= alpha <= 1, seed Eq. 27)
  bool active = false; ///< active in the solve that produced lambda
};

/// Whether the pair is active in the next solve. Only a pair whose node projects onto its facet can be active. An
/// active pair stays active while lambda - c g > -tol (its multiplier is compressive); an inactive pair becomes
/// active when it penetrates, lambda - c g > activate_tol (>= tol). c > 0 converts a gap to a force; the tolerances
/// are forces.
inline bool NextActive(const PairState &s, double c, double tol, double activate_tol) {
  const double score = s.lambda - c * s.gap;
  return s.inside && (s.active ? score > -tol : score > activate_tol);
}
inline bool NextActive(const PairState &s, double c, double tol) { return NextActive(s, c, tol, tol); }

} // namespace signorini
