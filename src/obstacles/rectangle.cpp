// A bounded plane (3D): a rectangle given by its centre, the normal into the body, an in-plane direction and its
// half-sizes, made of two oriented triangles (the facets of a meshed rigid surface).
#include "signorini/obstacles/obstacle.hpp"

#include <cmath>

namespace signorini {

ShapeType RectanglesShape() {
  return {"-obstacle_rectangles",
          "Bounded planes CX,CY,CZ,NX,NY,NZ,UX,UY,UZ,A,B,... (centre, normal into the body, a direction U in the "
          "plane, half-sizes A along U and B across it); two triangles each",
          11,
          [](const double *v, std::vector<std::unique_ptr<Facet>> &out) -> std::string {
            const double *c = v, *normal = v + 3, *dir = v + 6, a = v[9], b = v[10];
            // hypot: the squares of a long vector (1e200) would overflow and make it a zero one after normalising.
            const double nn = std::hypot(normal[0], normal[1], normal[2]);
            if (!(nn > 0)) return "has a zero normal";
            if (!(a > 0 && b > 0)) return "has a half-size that is not positive; expected A > 0 and B > 0";
            double n[3], u[3], w[3];
            for (int i = 0; i < 3; ++i) n[i] = normal[i] / nn;
            // U projected onto the plane, then W = N x U: (U, W, N) is right-handed, so U, W order the corners
            // counter-clockwise seen from the body and the triangles' normals point into it.
            const double un = dir[0] * n[0] + dir[1] * n[1] + dir[2] * n[2];
            for (int i = 0; i < 3; ++i) u[i] = dir[i] - un * n[i];
            const double nu = std::hypot(u[0], u[1], u[2]);
            const double nd = std::hypot(dir[0], dir[1], dir[2]);
            if (!(nu > 1e-8 * nd)) return "has a direction U along the normal; expected a direction in the plane";
            for (int i = 0; i < 3; ++i) u[i] /= nu;
            w[0] = n[1] * u[2] - n[2] * u[1], w[1] = n[2] * u[0] - n[0] * u[2], w[2] = n[0] * u[1] - n[1] * u[0];
            double p[4][3];
            const double su[4] = {-a, a, a, -a}, sw[4] = {-b, -b, b, b};
            for (int k = 0; k < 4; ++k)
              for (int i = 0; i < 3; ++i) p[k][i] = c[i] + su[k] * u[i] + sw[k] * w[i];
            out.push_back(std::make_unique<Triangle>(p[0], p[1], p[2]));
            out.push_back(std::make_unique<Triangle>(p[0], p[2], p[3]));
            return "";
          },
          3};
}

} // namespace signorini
