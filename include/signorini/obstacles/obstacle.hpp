// The rigid obstacle: a set of facets (2D: oriented segments, arcs as polylines, discs; 3D: planes, spheres,
// cylinders, triangles; meshed surfaces from gmsh files as segments or triangles), each of which computes the signed
// gap and the normal of a point. Sign convention: the normal points from the obstacle into the body;
// gap = n . (x - P) >= 0 is open, < 0 is penetration.
#pragma once

#include <petscsys.h>

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace signorini {

/// An axis-aligned box, lo and hi corners (the body's bounding box, over which unbounded obstacles are drawn).
struct Box {
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
};

/// A triangulated surface for output: three corners per triangle, each triangle's right-hand normal (corner order)
/// pointing into the body.
using TriangleSoup = std::vector<std::array<double, 3>>;

/// Closest-point data of a point x with respect to one facet.
struct Projection {
  double gap = 0;          ///< signed gap n . (x - P)
  double normal[3] = {};   ///< unit normal at P, pointing into the body
  double alpha = 0;        ///< position of the projection along the facet (segments, docs/theory.md §1: in [0, 1]
                           ///< inside; triangles: the smallest barycentric coordinate, >= 0 inside)
  bool inside = false;     ///< the projection falls on the facet (docs/theory.md §1), within the tolerance
};

/// The largest facet size that the alpha tolerance is relative to, as a fraction of the body's diagonal.
constexpr double EDGE_TOL_LENGTH = 0.1;

class Facet {
public:
  virtual ~Facet() = default;
  /// Projects the point x (dim values) on the facet. A bounded facet counts a foot up to alpha_tol times the smaller
  /// of its own size and EDGE_TOL_LENGTH `length` (the body's diagonal) past an edge as on it: relative to the facet
  /// as in docs/theory.md §1, but never farther than alpha_tol / 10 body diagonals (at most 1e-3 of them, the bound
  /// of the gap tolerances), so that a long facet does not hold a node far past its end (a floor 1e9 long held nodes
  /// 10 past its end with alpha_tol 1e-8).
  virtual Projection Project(const double *x, double alpha_tol, double length) const = 0;
  /// Euclidean distance from x to the facet (for the pair search).
  virtual double Distance(const double *x) const = 0;
  /// Axis-aligned bounding box (lo, hi: dim values each; infinite for an unbounded facet).
  virtual void Bounds(double *lo, double *hi) const = 0;
  virtual std::string Describe() const = 0;
  /// The centre of a flat facet of finite size (segment, triangle) into c (3 values), whether it has one: a smooth or
  /// unbounded shape has no joints with other facets.
  virtual bool Centroid(double *) const { return false; }
  /// The facet's shape for output in 2D: a polyline; a closed curve repeats its first point (empty in 3D).
  virtual std::vector<std::array<double, 2>> Polyline() const { return {}; }
  /// The facet's shape for output in 3D, triangulated (empty in 2D); an unbounded shape is drawn over the extent of
  /// the body's bounding box `body`.
  virtual TriangleSoup Surface(const Box &body) const = 0;
};

/// An oriented segment P0 -> P1; its normal is the left normal of the direction.
class Segment final : public Facet {
public:
  Segment(const double *p0, const double *p1);
  Projection Project(const double *x, double alpha_tol, double length) const override;
  double Distance(const double *x) const override;
  void Bounds(double *lo, double *hi) const override;
  std::string Describe() const override;
  std::vector<std::array<double, 2>> Polyline() const override;
  TriangleSoup Surface(const Box &) const override { return {}; }
  bool Centroid(double *c) const override;
  double Length() const { return length_; }

private:
  double p0_[2], p1_[2], n_[2], length_;
};

/// An oriented triangle P0, P1, P2 (3D), the flat facet of a meshed rigid surface; its normal
/// (P1 - P0) x (P2 - P0) / |.| follows the node order by the right-hand rule. Like a segment, its gap is the distance
/// to its plane, n . (x - P0), and `inside` says whether the foot of x on the plane falls on the triangle: its
/// barycentric coordinates are all >= -alpha_tol min(1, EDGE_TOL_LENGTH length / height) for the height onto each
/// edge (alpha: the smallest of them). Distance is the exact distance to the
/// closest point of the triangle (its interior, an edge or a vertex).
class Triangle final : public Facet {
public:
  Triangle(const double *p0, const double *p1, const double *p2);
  Projection Project(const double *x, double alpha_tol, double length) const override;
  double Distance(const double *x) const override;
  void Bounds(double *lo, double *hi) const override;
  std::string Describe() const override;
  TriangleSoup Surface(const Box &body) const override;
  bool Centroid(double *c) const override;
  /// The point of the triangle closest to x.
  void ClosestPoint(const double *x, double *c) const;
  double Area() const { return area_; }

private:
  /// Barycentric coordinates (of P0, P1, P2) of the foot of x on the triangle's plane.
  void Barycentric(const double *x, double *b) const;
  double p_[3][3], n_[3], area_;
  double height_[3]; ///< the height onto the edge opposite each corner (the barycentric coordinate's unit length)
  double gram_inv_[3]; ///< inverse of the Gram matrix of the edges P1 - P0, P2 - P0: (00, 01, 11)
};

/// A rigid ball (centre, radius) in dimension dim, the body outside it: a disc in 2D, a sphere in 3D; normals point
/// radially outwards.
class Ball final : public Facet {
public:
  Ball(const double *centre, double radius, int dim);
  Projection Project(const double *x, double alpha_tol, double length) const override;
  double Distance(const double *x) const override;
  void Bounds(double *lo, double *hi) const override;
  std::string Describe() const override;
  /// The circle as a polygon of POLYGON_SIDES sides (output only; the gap is exact).
  std::vector<std::array<double, 2>> Polyline() const override;
  /// The sphere as a UV sphere about the z axis (output only): SPHERE_MERIDIANS meridians, SPHERE_MERIDIANS / 2
  /// bands of latitude, 2 SPHERE_MERIDIANS (SPHERE_MERIDIANS / 2 - 1) triangles; its vertices include the six points
  /// of the sphere on the axes through its centre, so its bounds are the sphere's.
  TriangleSoup Surface(const Box &body) const override;
  static constexpr int POLYGON_SIDES = 128;
  static constexpr int SPHERE_MERIDIANS = 64;

private:
  double CentreDistance(const double *x) const;
  double c_[3] = {0, 0, 0}, r_;
  int dim_;
};

/// An unbounded plane (3D) through a point, its unit normal pointing into the body.
class Plane final : public Facet {
public:
  Plane(const double *point, const double *normal);
  Projection Project(const double *x, double alpha_tol, double length) const override;
  double Distance(const double *x) const override;
  void Bounds(double *lo, double *hi) const override;
  std::string Describe() const override;
  /// The rectangle of the plane that covers the projection of the body's bounding box (two triangles).
  TriangleSoup Surface(const Box &body) const override;

private:
  double p_[3], n_[3];
};

/// An infinite rigid cylinder (3D): a point on its axis, the axis, the radius; the body outside it.
class Cylinder final : public Facet {
public:
  Cylinder(const double *point, const double *axis, double radius);
  Projection Project(const double *x, double alpha_tol, double length) const override;
  double Distance(const double *x) const override;
  void Bounds(double *lo, double *hi) const override;
  std::string Describe() const override;
  /// The cylinder over the extent of the body's bounding box along its axis, as CYLINDER_SEGMENTS rectangles
  /// (2 CYLINDER_SEGMENTS triangles); the polygon of its section has a vertex on each side of both axes normal to
  /// the axis that TangentFrame gives.
  TriangleSoup Surface(const Box &body) const override;
  static constexpr int CYLINDER_SEGMENTS = 64;

private:
  /// The part r of x - P normal to the axis, and its length.
  double Radial(const double *x, double *r) const;
  double p_[3], a_[3], r_;
};

/// Two unit vectors t1, t2 completing the unit vector n to the right-handed orthonormal frame (t1, t2, n): t1 normal
/// to n and to the coordinate axis along which n has its smallest component, t2 = n x t1.
void TangentFrame(const double *n, double *t1, double *t2);
/// The range [lo, hi] of d . (x - origin) over the corners x of the box.
void BoxExtent(const Box &box, const double *origin, const double *d, double &lo, double &hi);
/// Appends the triangle (a, b, c) to out, in the corner order whose right-hand normal points along `into` (the
/// direction into the body).
void AppendTriangle(TriangleSoup &out, const std::array<double, 3> &a, const std::array<double, 3> &b,
                    const std::array<double, 3> &c, const double *into);

/// A shape type of the registry: the option that lists its items, how many numbers one item takes, how an item
/// becomes facets (an empty return is success, else the reason the item is invalid), and the mesh dimension it is for.
struct ShapeType {
  const char *option;
  const char *help;
  int numbers;
  std::function<std::string(const double *, std::vector<std::unique_ptr<Facet>> &)> build;
  int dim;
};

/// Registered shape types; adding a shape is one file plus one line in obstacle.cpp.
const std::vector<ShapeType> &ShapeRegistry();
ShapeType SegmentsShape();
ShapeType ArcsShape();
ShapeType DiscsShape();
ShapeType PlanesShape();
ShapeType SpheresShape();
ShapeType CylindersShape();
ShapeType RectanglesShape();

/// A meshed rigid surface given by -obstacle_mesh FILE[:GROUP]: the file as given, the physical group (empty: every
/// element of the obstacle's dimension) and where the file is looked for.
struct ObstacleMeshSource {
  std::string value; ///< the option's item as given
  std::string file, group;
  std::vector<std::string> paths, origins; ///< PathCandidates of the file
};

/// The kinds of obstacle, as -obstacle_friction names them: each shape type's option without "-obstacle_"
/// (segments, arcs, ...), in ShapeRegistry's order, then "mesh" (-obstacle_mesh, index MeshKind()).
std::vector<std::string> ObstacleKinds();
/// The kind of a shape type's facets and of a meshed obstacle's (indices into ObstacleKinds()).
int ShapeKind(const ShapeType &shape);
int MeshKind();

/// The obstacle: every facet of every shape given by the -obstacle_ options.
struct Obstacle {
  std::vector<std::unique_ptr<Facet>> facets;
  std::vector<int> facet_kind;           ///< per facet: its kind (index into ObstacleKinds())
  std::vector<const ShapeType *> shapes; ///< the shape types given
  std::vector<ObstacleMeshSource> meshes; ///< -obstacle_mesh items; their facets are added by LoadObstacleMeshes
  /// -obstacle_friction KIND:MU,...: per kind (ObstacleKinds()) its friction coefficient, -1: none given (the pairs
  /// on that kind take -contact_friction)
  std::vector<double> kind_friction;
  std::string friction_option; ///< -obstacle_friction as given (empty: not given), for messages
};

/// Reads the -obstacle_ options (one real array per shape type, and the -obstacle_mesh files). Collective.
[[nodiscard]] PetscErrorCode ReadObstacle(MPI_Comm comm, Obstacle &obstacle);

/// Refuses shapes made for another dimension than the mesh's dim (a segment on a 3D mesh, a plane on a 2D one),
/// naming the option and the shapes that fit. Collective.
[[nodiscard]] PetscErrorCode CheckObstacleDimension(MPI_Comm comm, const Obstacle &obstacle, int dim);

} // namespace signorini
