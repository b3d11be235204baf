// Circle arcs as polylines: centre, radius, start and end angle (degrees), number of segments.
#include "signorini/obstacles/obstacle.hpp"

#include "signorini/core/parse.hpp"

#include <cmath>
#include <string>

namespace signorini {

/// Segments of one arc: more would only cost memory and search time (a million segments resolve any radius).
constexpr double MAX_ARC_SEGMENTS = 1e6;
/// Bound of the angles (degrees): two turns either way write any arc in either direction, and a larger angle loses
/// the digits of its cosine (1e300 degrees has none left).
constexpr double MAX_ARC_ANGLE = 720;

ShapeType ArcsShape() {
  return {"-obstacle_arcs",
          "Arcs CX,CY,R,THETA0,THETA1,NSEG,... in degrees; counter-clockwise (THETA1 > THETA0) puts the body inside", 6,
          [](const double *v, std::vector<std::unique_ptr<Facet>> &out) -> std::string {
            const double r = v[2], sweep = v[4] - v[3];
            if (r <= 0) return "has radius " + FormatNumber(r) + " (expected > 0)";
            if (v[5] < 1 || v[5] != std::floor(v[5]) || v[5] > MAX_ARC_SEGMENTS)
              return "has " + FormatNumber(v[5]) + " segments (expected a whole number in [1, " +
                     FormatNumber(MAX_ARC_SEGMENTS) + "])";
            if (std::abs(v[3]) > MAX_ARC_ANGLE || std::abs(v[4]) > MAX_ARC_ANGLE)
              return "has angles " + FormatNumber(v[3]) + ", " + FormatNumber(v[4]) +
                     " (expected THETA0 and THETA1 in [" + FormatNumber(-MAX_ARC_ANGLE) + ", " +
                     FormatNumber(MAX_ARC_ANGLE) + "] degrees)";
            // More than a full turn would lay segments over each other (the obstacle on both sides of a node).
            if (sweep == 0 || std::abs(sweep) > 360)
              return "sweeps " + FormatNumber(sweep) + " degrees from THETA0 " + FormatNumber(v[3]) + " to THETA1 " +
                     FormatNumber(v[4]) + " (expected 0 < |THETA1 - THETA0| <= 360: positive counter-clockwise, "
                     "negative clockwise, at most a full turn)";
            const int n = (int)v[5];
            // A segment spanning half a turn or more has its normal on the wrong side of the circle (a full turn in
            // one segment has zero length, in two the segments lie on each other).
            if (std::abs(sweep) / n >= 180)
              return "has " + std::to_string(n) + " segment(s) for a sweep of " + FormatNumber(sweep) +
                     " degrees (expected each segment to span less than 180 degrees: NSEG > |THETA1 - THETA0| / 180)";
            const double t0 = v[3] * M_PI / 180, t1 = v[4] * M_PI / 180;
            const bool closed = std::abs(sweep) == 360;
            for (int k = 0; k < n; ++k) {
              // A full turn ends exactly where it starts (a closed polygon, no gap of a rounding error).
              const double a = t0 + (t1 - t0) * k / n, b = closed && k + 1 == n ? t0 : t0 + (t1 - t0) * (k + 1) / n;
              const double p0[2] = {v[0] + r * std::cos(a), v[1] + r * std::sin(a)};
              const double p1[2] = {v[0] + r * std::cos(b), v[1] + r * std::sin(b)};
              out.push_back(std::make_unique<Segment>(p0, p1));
            }
            return "";
          },
          2};
}

} // namespace signorini
