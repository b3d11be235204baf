// Circle arcs as polylines: centre, radius, start and end angle (degrees), number of segments.
#include "signorini/obstacles/obstacle.hpp"

#include "signorini/core/parse.hpp"

#include <cmath>

namespace signorini {

/// Segments of one arc: more would only cost memory and search time (a million segments resolve any radius).
constexpr double MAX_ARC_SEGMENTS = 1e6;

ShapeType ArcsShape() {
  return {"-obstacle_arcs",
          "Arcs CX,CY,R,THETA0,THETA1,NSEG,... in degrees; counter-clockwise (THETA1 > THETA0) puts the body inside", 6,
          [](const double *v, std::vector<std::unique_ptr<Facet>> &out) -> std::string {
            const double r = v[2], t0 = v[3] * M_PI / 180, t1 = v[4] * M_PI / 180;
            if (r <= 0) return "has radius " + FormatNumber(r) + " (expected > 0)";
            if (v[5] < 1 || v[5] != std::floor(v[5]) || v[5] > MAX_ARC_SEGMENTS)
              return "has " + FormatNumber(v[5]) + " segments (expected a whole number in [1, " +
                     FormatNumber(MAX_ARC_SEGMENTS) + "])";
            if (t0 == t1) return "has equal start and end angles";
            const int n = (int)v[5];
            for (int k = 0; k < n; ++k) {
              const double a = t0 + (t1 - t0) * k / n, b = t0 + (t1 - t0) * (k + 1) / n;
              const double p0[2] = {v[0] + r * std::cos(a), v[1] + r * std::sin(a)};
              const double p1[2] = {v[0] + r * std::cos(b), v[1] + r * std::sin(b)};
              out.push_back(std::make_unique<Segment>(p0, p1));
            }
            return "";
          },
          2};
}

} // namespace signorini
