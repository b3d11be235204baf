// The rigid obstacle: a set of facets (oriented segments, arcs as polylines, discs), each of which computes the
// signed gap and the normal of a point. Sign convention: the normal points from the obstacle into the body;
// gap = n . (x - P) >= 0 is open, < 0 is penetration.
#pragma once

#include <petscsys.h>

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace signorini {

/// Closest-point data of a point x with respect to one facet.
struct Projection {
  double gap = 0;          ///< signed gap n . (x - P)
  double normal[3] = {};   ///< unit normal at P, pointing into the body
  double alpha = 0;        ///< position of the projection along the facet (segments: Eq. 24, in [0, 1] inside)
  bool inside = false;     ///< the projection falls on the facet (seed Fig. 4), within the tolerance
};

class Facet {
public:
  virtual ~Facet() = default;
  /// Projects the point x (dim values) on the facet; alpha_tol widens the facet's parameter range.
  virtual Projection Project(const double *x, double alpha_tol) const = 0;
  /// Euclidean distance from x to the facet (for the pair search).
  virtual double Distance(const double *x) const = 0;
  /// Axis-aligned bounding box (lo, hi: dim values each).
  virtual void Bounds(double *lo, double *hi) const = 0;
  virtual std::string Describe() const = 0;
  /// The facet's shape for output: a polyline (dim values per point); a closed curve repeats its first point.
  virtual std::vector<std::array<double, 2>> Polyline() const = 0;
};

/// An oriented segment P0 -> P1; its normal is the left normal of the direction.
class Segment final : public Facet {
public:
  Segment(const double *p0, const double *p1);
  Projection Project(const double *x, double alpha_tol) const override;
  double Distance(const double *x) const override;
  void Bounds(double *lo, double *hi) const override;
  std::string Describe() const override;
  std::vector<std::array<double, 2>> Polyline() const override;
  double Length() const { return length_; }

private:
  double p0_[2], p1_[2], n_[2], length_;
};

/// A rigid disc (centre, radius), the body outside it; normals point radially outwards.
class Disc final : public Facet {
public:
  Disc(const double *centre, double radius);
  Projection Project(const double *x, double alpha_tol) const override;
  double Distance(const double *x) const override;
  void Bounds(double *lo, double *hi) const override;
  std::string Describe() const override;
  /// The circle as a polygon of POLYGON_SIDES sides (output only; the gap is exact).
  std::vector<std::array<double, 2>> Polyline() const override;
  static constexpr int POLYGON_SIDES = 128;

private:
  double c_[2], r_;
};

/// A shape type of the registry: the option that lists its items, how many numbers one item takes, and how an item
/// becomes facets (an empty return is success, else the reason the item is invalid).
struct ShapeType {
  const char *option;
  const char *help;
  int numbers;
  std::function<std::string(const double *, std::vector<std::unique_ptr<Facet>> &)> build;
};

/// Registered shape types; adding a shape is one file plus one line in obstacle.cpp.
const std::vector<ShapeType> &ShapeRegistry();
ShapeType SegmentsShape();
ShapeType ArcsShape();
ShapeType DiscsShape();

/// The obstacle: every facet of every shape given by the -obstacle_ options.
struct Obstacle {
  std::vector<std::unique_ptr<Facet>> facets;
};

/// Reads the -obstacle_ options (one real array per shape type). Collective.
[[nodiscard]] PetscErrorCode ReadObstacle(MPI_Comm comm, Obstacle &obstacle);

} // namespace signorini
