// The dual mortar rows of the -contact_pairs interfaces (mortar.hpp) and their master terms.
#include "signorini/contact/mortar.hpp"

#include "signorini/core/blocks.hpp"
#include "signorini/obstacles/obstacle.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>

namespace signorini {

namespace {

using GatheredFace = MortarCoupling::Facet;

/// Every rank's faces of the group `name` (input: the option item, for messages), gathered on every rank: the
/// interface is a surface of the mesh, small beside the volume. u_local (dim values per local vertex; null: none):
/// the displacement of the current configuration. Collective.
PetscErrorCode GatherFaces(const Mesh &mesh, const std::string &name, const std::string &input, const double *u_local,
                           std::vector<GatheredFace> &out) {
  const int dim = mesh.Dim();
  constexpr int WIDTH = 1 + 4 + 12 + 4 + 12; // n, nodes, coordinates, bodies, displacements
  std::vector<Face> faces;
  PetscFunctionBeginUser;
  PetscCall(mesh.GroupFaces(name, faces, input));
  std::vector<double> mine;
  for (const Face &f : faces) {
    std::array<double, WIDTH> rec{};
    rec[0] = f.n;
    for (int a = 0; a < f.n; ++a) {
      rec[1 + a] = (double)mesh.VertexOriginal(f.v[a]);
      for (int d = 0; d < dim; ++d) rec[5 + 3 * a + d] = mesh.X(f.v[a])[d];
      rec[17 + a] = (double)mesh.VertexBody(f.v[a]);
      for (int d = 0; d < dim && u_local; ++d) rec[21 + 3 * a + d] = u_local[f.v[a] * dim + d];
    }
    mine.insert(mine.end(), rec.begin(), rec.end());
  }
  std::vector<double> all;
  PetscCall(AllGather(mesh.Comm(), mine, all));
  out.clear();
  for (std::size_t i = 0; i < all.size(); i += WIDTH) {
    GatheredFace g;
    g.n = (int)all[i];
    for (int a = 0; a < g.n; ++a) {
      g.node[a] = (PetscInt)all[i + 1 + a];
      for (int d = 0; d < 3; ++d) g.X[a][d] = all[i + 5 + 3 * a + d], g.x[a][d] = g.X[a][d] + all[i + 21 + 3 * a + d];
      g.body[a] = (PetscInt)all[i + 17 + a];
    }
    out.push_back(g);
  }
  PetscFunctionReturn(0);
}

/// A segment's geometry (2D): length, unit tangent and outward normal (the body on the left of node 0 -> node 1).
struct SegmentFrame {
  double length, t[2], n[2];
  explicit SegmentFrame(const GatheredFace &f) {
    const double dx = f.x[1][0] - f.x[0][0], dy = f.x[1][1] - f.x[0][1];
    length = std::hypot(dx, dy);
    t[0] = dx / length, t[1] = dy / length;
    n[0] = t[1], n[1] = -t[0];
  }
};

/// A facet's plane (3D): centre, outward unit normal (of the diagonals' cross product for a quadrilateral), area, and
/// a tangent basis; coordinates of a point in the plane, its height over it.
struct FacetPlane {
  double c[3] = {0, 0, 0}, n[3], t1[3], t2[3], area;
  explicit FacetPlane(const GatheredFace &f) {
    for (int a = 0; a < f.n; ++a)
      for (int d = 0; d < 3; ++d) c[d] += f.x[a][d] / f.n;
    const auto &x = f.x;
    double u[3], v[3];
    for (int d = 0; d < 3; ++d)
      u[d] = x[f.n == 4 ? 2 : 1][d] - x[0][d], v[d] = x[f.n == 4 ? 3 : 2][d] - x[f.n == 4 ? 1 : 0][d];
    const double w[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double len = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    area = 0.5 * len; // of a triangle, and of a planar quadrilateral (half the diagonals' cross product)
    for (int d = 0; d < 3; ++d) n[d] = w[d] / len;
    TangentFrame(n, t1, t2);
  }
  std::array<double, 2> In(const std::array<double, 3> &x) const {
    double r[2] = {0, 0};
    for (int d = 0; d < 3; ++d) r[0] += (x[d] - c[d]) * t1[d], r[1] += (x[d] - c[d]) * t2[d];
    return {r[0], r[1]};
  }
  double Height(const std::array<double, 3> &x) const {
    double h = 0;
    for (int d = 0; d < 3; ++d) h += (x[d] - c[d]) * n[d];
    return h;
  }
};

/// The master facets' bounding boxes (lo, hi) and outward normals, computed once per interface.
struct MasterBoxes {
  std::vector<std::array<double, 6>> box;
  std::vector<std::array<double, 3>> normal;
  explicit MasterBoxes(const std::vector<GatheredFace> &masters) {
    for (const GatheredFace &f : masters) {
      std::array<double, 6> b{1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
      for (int a = 0; a < f.n; ++a)
        for (int d = 0; d < 3; ++d) b[d] = std::min(b[d], f.x[a][d]), b[3 + d] = std::max(b[3 + d], f.x[a][d]);
      box.push_back(b);
      if (f.n == 2) {
        const SegmentFrame p(f);
        normal.push_back({p.n[0], p.n[1], 0});
      } else {
        const FacetPlane p(f);
        normal.push_back({p.n[0], p.n[1], p.n[2]});
      }
    }
  }
};

/// One point of the overlap of a slave facet with a master facet: its weight (length or area) and both sides' shape
/// functions.
struct OverlapPoint {
  double w, Ns[4], Nm[4];
  std::size_t master;
};

/// Two-point Gauss rule on [0, 1]: exact for the products of two linear functions that the mortar integrals hold.
constexpr double GAUSS_X[2] = {0.21132486540518713, 0.78867513459481287};
constexpr double GAUSS_W[2] = {0.5, 0.5};

/// The quadrature points of slave segment s's overlap with the master segments (2D): each master segment with an
/// opposite normal is projected along the slave segment's normal onto it; the part of the slave segment it covers
/// (parameter xi in [lo, hi], the master running from xi_c to xi_d) is integrated by 2 Gauss points, exact for the
/// products of two linear functions. An overlap whose master point is farther than radius along the normal (at the
/// middle of the overlap) is left out.
void SegmentOverlap(const GatheredFace &s, const std::vector<GatheredFace> &masters, const MasterBoxes &boxes,
                    double radius, std::vector<OverlapPoint> &points) {
  const SegmentFrame fs(s);
  double lo2[2], hi2[2]; // the slave segment's box, widened by the radius
  for (int d = 0; d < 2; ++d)
    lo2[d] = std::min(s.x[0][d], s.x[1][d]) - radius, hi2[d] = std::max(s.x[0][d], s.x[1][d]) + radius;
  points.clear();
  for (std::size_t m = 0; m < masters.size(); ++m) {
    const auto &box = boxes.box[m];
    const auto &nm = boxes.normal[m];
    if (box[3] < lo2[0] || box[0] > hi2[0] || box[4] < lo2[1] || box[1] > hi2[1]) continue;
    if (fs.n[0] * nm[0] + fs.n[1] * nm[1] >= 0) continue;
    const GatheredFace &f = masters[m];
    double xi[2];
    for (int a = 0; a < 2; ++a)
      xi[a] = ((f.x[a][0] - s.x[0][0]) * fs.t[0] + (f.x[a][1] - s.x[0][1]) * fs.t[1]) / fs.length;
    if (std::abs(xi[1] - xi[0]) < 1e-12) continue;
    const double lo = std::max(0.0, std::min(xi[0], xi[1])), hi = std::min(1.0, std::max(xi[0], xi[1]));
    if (hi - lo <= 1e-12) continue;
    // The normal distance at the middle of the overlap.
    const double mid = 0.5 * (lo + hi), eta = (mid - xi[0]) / (xi[1] - xi[0]);
    double h = 0;
    for (int d = 0; d < 2; ++d) {
      const double xs = s.x[0][d] + mid * (s.x[1][d] - s.x[0][d]), xm = f.x[0][d] + eta * (f.x[1][d] - f.x[0][d]);
      h += (xs - xm) * fs.n[d];
    }
    if (std::abs(h) > radius) continue;
    for (int q = 0; q < 2; ++q) {
      const double x = lo + GAUSS_X[q] * (hi - lo), e = (x - xi[0]) / (xi[1] - xi[0]);
      points.push_back({GAUSS_W[q] * (hi - lo) * fs.length, {1 - x, x, 0, 0}, {1 - e, e, 0, 0}, m});
    }
  }
}

using Polygon = std::vector<std::array<double, 2>>;

double Cross(const std::array<double, 2> &o, const std::array<double, 2> &a, const std::array<double, 2> &b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

double Area(const Polygon &p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto &u = p[i], &v = p[(i + 1) % p.size()];
    a += u[0] * v[1] - u[1] * v[0];
  }
  return 0.5 * a;
}

/// The polygon's corners in counter-clockwise order.
Polygon CounterClockwise(const Polygon &p) { return Area(p) >= 0 ? p : Polygon(p.rbegin(), p.rend()); }

/// The part of the polygon `subject` inside the convex polygon `clip` (both counter-clockwise): Sutherland-Hodgman.
Polygon Clip(Polygon subject, const Polygon &clip) {
  for (std::size_t e = 0; e < clip.size() && !subject.empty(); ++e) {
    const auto &a = clip[e], &b = clip[(e + 1) % clip.size()];
    Polygon out;
    for (std::size_t i = 0; i < subject.size(); ++i) {
      const auto &p = subject[i], &q = subject[(i + 1) % subject.size()];
      const double sp = Cross(a, b, p), sq = Cross(a, b, q);
      if (sp >= 0) out.push_back(p);
      if ((sp >= 0) != (sq >= 0)) {
        const double t = sp / (sp - sq);
        out.push_back({p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])});
      }
    }
    subject = std::move(out);
  }
  return subject;
}

/// The shape functions at the point q of a facet's projection (corners p, in the facet's node order): barycentric
/// coordinates of a triangle, bilinear functions of a quadrilateral at its reference coordinates (Newton's method on
/// the bilinear map; corners at (-1,-1), (1,-1), (1,1), (-1,1)).
void ShapeAt(const Polygon &p, const std::array<double, 2> &q, double *N) {
  if (p.size() == 3) {
    const double det = Cross(p[0], p[1], p[2]);
    N[1] = Cross(p[0], q, p[2]) / det;
    N[2] = Cross(p[0], p[1], q) / det;
    N[0] = 1 - N[1] - N[2];
    return;
  }
  static const double corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  double xi[2] = {0, 0};
  for (int it = 0; it < 30; ++it) {
    double r[2] = {-q[0], -q[1]}, J[2][2] = {{0, 0}, {0, 0}};
    for (int k = 0; k < 4; ++k) {
      const double a = 1 + corner[k][0] * xi[0], b = 1 + corner[k][1] * xi[1];
      for (int d = 0; d < 2; ++d) {
        r[d] += 0.25 * a * b * p[k][d];
        J[d][0] += 0.25 * corner[k][0] * b * p[k][d];
        J[d][1] += 0.25 * a * corner[k][1] * p[k][d];
      }
    }
    const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    const double d0 = (J[1][1] * r[0] - J[0][1] * r[1]) / det, d1 = (J[0][0] * r[1] - J[1][0] * r[0]) / det;
    xi[0] -= d0, xi[1] -= d1;
    if (std::abs(d0) + std::abs(d1) < 1e-15) break;
  }
  for (int k = 0; k < 4; ++k) N[k] = 0.25 * (1 + corner[k][0] * xi[0]) * (1 + corner[k][1] * xi[1]);
}

/// Dunavant's 7-point rule on a triangle (degree 5): barycentric points and weights summing to 1.
constexpr double TRI_A[7] = {1.0 / 3, 0.059715871789770, 0.470142064105115, 0.470142064105115,
                             0.797426985353087, 0.101286507323456, 0.101286507323456};
constexpr double TRI_B[7] = {1.0 / 3, 0.470142064105115, 0.059715871789770, 0.470142064105115,
                             0.101286507323456, 0.797426985353087, 0.101286507323456};
constexpr double TRI_W[7] = {0.225, 0.132394152788506, 0.132394152788506, 0.132394152788506,
                             0.125939180544827, 0.125939180544827, 0.125939180544827};

/// The quadrature points of slave facet s's overlap with the master facets (3D): each master facet with an opposite
/// normal is projected along the slave facet's normal onto its plane and clipped against the slave facet (both
/// convex), the overlap polygon split into triangles from its centre, each integrated by Dunavant's rule: exact for
/// the products of linear functions on triangles and parallelograms, a quadrature of degree 5 of those of a general
/// quadrilateral's (its bilinear map is not affine). An overlap whose master point is farther than radius along the
/// normal is left out.
void FacetOverlap(const GatheredFace &s, const std::vector<GatheredFace> &masters, const MasterBoxes &boxes,
                  double radius, std::vector<OverlapPoint> &points) {
  const FacetPlane plane(s);
  Polygon S(s.n);
  double lo[3], hi[3], lo2[2] = {1e300, 1e300}, hi2[2] = {-1e300, -1e300};
  for (int d = 0; d < 3; ++d) lo[d] = 1e300, hi[d] = -1e300;
  for (int a = 0; a < s.n; ++a) {
    S[a] = plane.In(s.x[a]);
    for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], s.x[a][d] - radius), hi[d] = std::max(hi[d], s.x[a][d] + radius);
    for (int d = 0; d < 2; ++d) lo2[d] = std::min(lo2[d], S[a][d]), hi2[d] = std::max(hi2[d], S[a][d]);
  }
  const Polygon Sccw = CounterClockwise(S);
  points.clear();
  for (std::size_t m = 0; m < masters.size(); ++m) {
    // Cheap rejections first (this loop meets every master facet): the bounding boxes, the normals' orientation, the
    // boxes of the projections on the slave facet's plane.
    const auto &box = boxes.box[m];
    bool near = true;
    for (int d = 0; d < 3 && near; ++d) near = box[3 + d] >= lo[d] && box[d] <= hi[d];
    if (!near) continue;
    const auto &nm = boxes.normal[m];
    if (nm[0] * plane.n[0] + nm[1] * plane.n[1] + nm[2] * plane.n[2] >= 0) continue;
    const GatheredFace &f = masters[m];
    std::array<std::array<double, 2>, 4> xm;
    double mlo[2] = {1e300, 1e300}, mhi[2] = {-1e300, -1e300};
    for (int a = 0; a < f.n; ++a) {
      xm[a] = plane.In(f.x[a]);
      for (int d = 0; d < 2; ++d) mlo[d] = std::min(mlo[d], xm[a][d]), mhi[d] = std::max(mhi[d], xm[a][d]);
    }
    if (mhi[0] <= lo2[0] || mlo[0] >= hi2[0] || mhi[1] <= lo2[1] || mlo[1] >= hi2[1]) continue;
    const Polygon Mpoly(xm.begin(), xm.begin() + f.n);
    double height[4];
    for (int a = 0; a < f.n; ++a) height[a] = plane.Height(f.x[a]);
    // The master's outward normal opposes the slave's: its corners run clockwise in the slave's plane.
    const Polygon ccw = CounterClockwise(Mpoly);
    if (std::abs(Area(Mpoly)) <= 1e-12 * Area(Sccw)) continue; // edge-on in this projection
    const Polygon overlap = Clip(Sccw, ccw);
    if (overlap.size() < 3 || Area(overlap) <= 1e-12 * Area(Sccw)) continue;
    std::array<double, 2> centre{0, 0};
    for (const auto &p : overlap) centre[0] += p[0] / overlap.size(), centre[1] += p[1] / overlap.size();
    double Nc[4], h = 0;
    ShapeAt(Mpoly, centre, Nc);
    for (int a = 0; a < f.n; ++a) h += Nc[a] * height[a];
    if (std::abs(h) > radius) continue;
    for (std::size_t i = 0; i < overlap.size(); ++i) {
      const auto &p = overlap[i], &q = overlap[(i + 1) % overlap.size()];
      const double area = 0.5 * Cross(centre, p, q);
      if (area <= 0) continue;
      for (int g = 0; g < 7; ++g) {
        const double b = TRI_B[g], c = 1 - TRI_A[g] - TRI_B[g];
        const std::array<double, 2> x{TRI_A[g] * centre[0] + b * p[0] + c * q[0],
                                      TRI_A[g] * centre[1] + b * p[1] + c * q[1]};
        OverlapPoint o;
        o.w = TRI_W[g] * area, o.master = m;
        ShapeAt(S, x, o.Ns);
        ShapeAt(Mpoly, x, o.Nm);
        points.push_back(o);
      }
    }
  }
}

/// Solves the n x n system A X = B (row major, B with n columns) in place by Gaussian elimination with partial
/// pivoting; false when a pivot vanishes.
bool Solve(int n, double *A, double *B) {
  for (int k = 0; k < n; ++k) {
    int piv = k;
    for (int i = k + 1; i < n; ++i)
      if (std::abs(A[i * n + k]) > std::abs(A[piv * n + k])) piv = i;
    if (!(std::abs(A[piv * n + k]) > 0)) return false;
    for (int j = 0; j < n; ++j) std::swap(A[k * n + j], A[piv * n + j]), std::swap(B[k * n + j], B[piv * n + j]);
    for (int i = k + 1; i < n; ++i) {
      const double f = A[i * n + k] / A[k * n + k];
      for (int j = 0; j < n; ++j) A[i * n + j] -= f * A[k * n + j], B[i * n + j] -= f * B[k * n + j];
    }
  }
  for (int k = n - 1; k >= 0; --k)
    for (int j = 0; j < n; ++j) {
      double v = B[k * n + j];
      for (int i = k + 1; i < n; ++i) v -= A[k * n + i] * B[i * n + j];
      B[k * n + j] = v / A[k * n + k];
    }
  return true;
}

/// What the slave facets accumulate per slave node (file numbering): D_jj, M_jl per master node l, and the interface's
/// normal weighted by N_j over the overlap (the row's normal, InterfaceNormal).
struct Integrals {
  std::map<PetscInt, double> D;
  std::map<PetscInt, std::map<PetscInt, double>> M;
  std::map<PetscInt, std::array<double, 3>> normal;
};

/// The contribution of slave facet s (its measure: length or area) to D, M and the rows' normals from the points of
/// its overlap with the master facets (SegmentOverlap, FacetOverlap), with the dual basis biorthogonal on the
/// overlap: psi_i = sum_k A_ik N_k, A = De Me^-1, De_i = int N_i, Me_ik = int N_i N_k (Me symmetric, so
/// A^T = Me^-1 De solves for it).
/// The normal of the interface where a slave facet (outward normal ns, compliance cs) meets a master facet (outward
/// normal nm, compliance cm), pointing from the master into the slave: the two surfaces' normals weighted by the other
/// side's share of the compliance, (cs nm - cm ns) / (cs + cm) (not normalised). Two bodies pressed together meet along
/// the surface between their undeformed shapes that their compliances give (Hertz: each side's normal displacement is
/// in proportion to its (1 - nu^2) / E): the master's own surface for a rigid master (cm = 0), the midway surface
/// between two equal bodies. With the master's normal alone the linear model pushed two equal cylinders apart along
/// the interface by p x / R (the tilt of the master's surface), a spurious relative slip of 35 % of their tangential
/// displacement under a normal load, which friction turned into a tangential traction of 25 % of mu p0.
void InterfaceNormal(const double *nm, const double *ns, double cs, double cm, double *n) {
  const double ws = cs + cm > 0 ? cm / (cs + cm) : 0.0;
  for (int d = 0; d < 3; ++d) n[d] = (1 - ws) * nm[d] - ws * ns[d];
}

/// ns, cs: the slave facet's outward normal and compliance; compliance: per body (empty: the master's normal alone).
void OverlapIntegrals(const GatheredFace &s, double measure, const std::vector<GatheredFace> &masters,
                      const MasterBoxes &boxes, const std::vector<OverlapPoint> &points, const double *ns,
                      const std::vector<double> &compliance, Integrals &in) {
  const int n = s.n;
  double Me[16] = {0}, De[4] = {0}, covered = 0;
  for (const OverlapPoint &o : points) {
    covered += o.w;
    for (int i = 0; i < n; ++i) {
      De[i] += o.w * o.Ns[i];
      for (int k = 0; k < n; ++k) Me[i * n + k] += o.w * o.Ns[i] * o.Ns[k];
    }
  }
  // An overlap of a few 1e-9 of the facet carries no weight worth its ill-conditioned basis.
  if (covered < 1e-9 * measure) return;
  double At[16] = {0}; // A^T = Me^-1 De
  for (int i = 0; i < n; ++i) At[i * n + i] = De[i];
  if (!Solve(n, Me, At)) return;
  for (int i = 0; i < n; ++i) in.D[s.node[i]] += De[i];
  const double cs = compliance.empty() ? 0.0 : compliance[s.body[0]];
  for (const OverlapPoint &o : points) {
    const GatheredFace &m = masters[o.master];
    double nm[3];
    InterfaceNormal(boxes.normal[o.master].data(), ns, cs, compliance.empty() ? 0.0 : compliance[m.body[0]], nm);
    for (int i = 0; i < n; ++i) {
      double psi = 0;
      for (int k = 0; k < n; ++k) psi += At[k * n + i] * o.Ns[k];
      for (int l = 0; l < m.n; ++l) in.M[s.node[i]][m.node[l]] += o.w * psi * o.Nm[l];
      for (int d = 0; d < 3; ++d) in.normal[s.node[i]][d] += o.w * o.Ns[i] * nm[d];
    }
  }
}

/// The integrals of the slave facets `slaves` (2D: segments) with the master facets `masters`: D, M and the rows'
/// normals per slave node (OverlapIntegrals), each slave node's tributary measure (if given), and per slave facet the
/// master facets its overlap meets (if given).
void SlaveIntegrals(int dim, const std::vector<GatheredFace> &slaves, const std::vector<GatheredFace> &masters,
                    double radius, const std::vector<double> &compliance, Integrals &in,
                    std::map<PetscInt, double> *tributary, std::vector<std::vector<std::size_t>> *hit) {
  std::vector<OverlapPoint> points;
  const MasterBoxes boxes(masters);
  if (hit) hit->assign(slaves.size(), {});
  for (std::size_t i = 0; i < slaves.size(); ++i) {
    const GatheredFace &s = slaves[i];
    double measure, ns[3] = {0, 0, 0};
    if (dim == 2) {
      const SegmentFrame f(s);
      measure = f.length, ns[0] = f.n[0], ns[1] = f.n[1];
    } else {
      const FacetPlane f(s);
      measure = f.area, ns[0] = f.n[0], ns[1] = f.n[1], ns[2] = f.n[2];
    }
    if (tributary)
      for (int a = 0; a < s.n; ++a) (*tributary)[s.node[a]] += measure / s.n;
    if (dim == 2) SegmentOverlap(s, masters, boxes, radius, points);
    else FacetOverlap(s, masters, boxes, radius, points);
    OverlapIntegrals(s, measure, masters, boxes, points, ns, compliance, in);
    if (hit)
      for (const OverlapPoint &o : points)
        if ((*hit)[i].empty() || (*hit)[i].back() != o.master) (*hit)[i].push_back(o.master);
  }
}

/// Slave node j's share of the integrals (D_jj, M_jl, the normal's sum), summed over slave facets.
struct RowSums {
  double D = 0;
  std::map<PetscInt, double> M;
  std::array<double, 3> normal{0, 0, 0};
  void Add(const RowSums &o) {
    D += o.D;
    for (const auto &[l, m] : o.M) M[l] += m;
    for (int d = 0; d < 3; ++d) normal[d] += o.normal[d];
  }
};

/// Node j's share of the integrals of slave facet s with the master facets `masters` (SlaveIntegrals).
RowSums FacetShare(int dim, PetscInt j, const GatheredFace &s, const std::vector<GatheredFace> &masters, double radius,
                   const std::vector<double> &compliance) {
  Integrals in;
  SlaveIntegrals(dim, {s}, masters, radius, compliance, in, nullptr, nullptr);
  RowSums r;
  if (const auto it = in.D.find(j); it != in.D.end()) r.D = it->second;
  if (const auto it = in.M.find(j); it != in.M.end()) r.M = it->second;
  if (const auto it = in.normal.find(j); it != in.normal.end()) r.normal = it->second;
  return r;
}

/// The row of slave node j from its sums: its unit normal n, and its coefficients c (dim values per node of `nodes`:
/// -n on j, w_jl n = M_jl / D_jj n on a master node l, 0 elsewhere) and weighted gap g = n . (x_j - sum_l w_jl x_l) at
/// the positions x (dim values per node of `nodes`); false if j has no integrals.
bool RowOf(int dim, PetscInt j, const RowSums &in, const std::vector<PetscInt> &nodes, const std::vector<double> &x,
           std::vector<double> &c, double &g) {
  const auto &nv = in.normal;
  const double len = std::sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
  if (!(in.D > 0) || !(len > 0)) return false;
  double n[3] = {nv[0] / len, nv[1] / len, nv[2] / len};
  c.assign(nodes.size() * dim, 0.0);
  g = 0;
  for (std::size_t a = 0; a < nodes.size(); ++a) {
    double w = nodes[a] == j ? -1.0 : 0.0;
    if (nodes[a] != j) {
      const auto l = in.M.find(nodes[a]);
      if (l != in.M.end()) w = l->second / in.D;
    }
    for (int k = 0; k < dim; ++k) c[a * dim + k] = w * n[k], g -= w * n[k] * x[a * dim + k];
  }
  return true;
}

/// The mortar log events: the rows (Build) and svk's consistent tangent (Linearise), of one class.
PetscLogEvent EV_MORTAR = 0, EV_TANGENT = 0;
PetscErrorCode RegisterEvents() {
  PetscFunctionBeginUser;
  if (EV_MORTAR) PetscFunctionReturn(0);
  PetscClassId id;
  PetscCall(PetscClassIdRegister("signorini mortar", &id));
  PetscCall(PetscLogEventRegister("SigMortar", id, &EV_MORTAR));
  PetscCall(PetscLogEventRegister("SigMortarTangent", id, &EV_TANGENT));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode MortarCoupling::Build(const Mesh &mesh, const ContactOptions &opts, const std::vector<char> &fixed,
                                     PetscInt facet_base, const double *u_local) {
  PetscFunctionBeginUser;
  PetscCall(RegisterEvents());
  PetscCall(PetscLogEventBegin(EV_MORTAR, 0, 0, 0, 0));
  dim_ = mesh.Dim();
  interfaces_ = (PetscInt)opts.pairs.size();
  facet_base_ = facet_base;
  rows_.clear();
  slave_.assign(mesh.NumLocalVertices(), 0);
  master_vertex_.assign(mesh.NumLocalVertices(), 0);
  for (PetscInt i = 0; i < interfaces_; ++i) {
    const std::size_t first = rows_.size();
    PetscCall(BuildInterface(mesh, opts, fixed, i, u_local));
    if (!u_local) PetscCall(CheckInterface(mesh, opts, i, first));
  }
  PetscCall(PetscLogEventEnd(EV_MORTAR, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode MortarCoupling::CheckInterface(const Mesh &mesh, const ContactOptions &opts, PetscInt item,
                                              std::size_t first) const {
  const auto &[slave, master] = opts.pairs[item];
  MPI_Comm comm = mesh.Comm();
  PetscFunctionBeginUser;
  // A pair whose sides are nowhere within the search radius of each other is most likely a wrong group or a wrong
  // radius: no row would ever constrain it.
  PetscInt count = (PetscInt)(rows_.size() - first);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &count, 1, MPIU_INT, MPI_SUM, comm));
  PetscCheck(count > 0, comm, PETSC_ERR_USER_INPUT,
             "-contact_pairs %s:%s: no facet of '%s' faces a facet of '%s' within the search radius %g (opposite "
             "normals, overlapping along the normal); expected the facing sides of two bodies, or a larger "
             "-contact_search_radius", slave.c_str(), master.c_str(), slave.c_str(), master.c_str(),
             opts.search_radius);
  // Bodies that start inside each other by more than START_OVERLAP body diagonals: the mesh is wrong (a body placed
  // at the wrong height, a group on the wrong side), not a contact to resolve.
  struct {
    double depth;
    int rank;
  } mine{0, 0}, deepest;
  PetscCallMPI(MPI_Comm_rank(comm, &mine.rank));
  PetscInt node = -1;
  for (std::size_t r = first; r < rows_.size(); ++r)
    if (-rows_[r].g0 > mine.depth) mine.depth = -rows_[r].g0, node = mesh.VertexOriginal(rows_[r].vertex) + 1;
  PetscCallMPI(MPI_Allreduce(&mine, &deepest, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm));
  PetscCallMPI(MPI_Bcast(&node, 1, MPIU_INT, deepest.rank, comm));
  PetscCheck(deepest.depth <= START_OVERLAP * opts.length, comm, PETSC_ERR_USER_INPUT,
             "-contact_pairs %s:%s: the bodies start inside each other: slave node %" PetscInt_FMT " (in file order) is "
             "%g deep in '%s' (weighted gap %g); expected bodies that touch or stand apart at the start, overlapping "
             "by at most %g body diagonals (%g)", slave.c_str(), master.c_str(), node, deepest.depth, master.c_str(),
             -deepest.depth, START_OVERLAP, START_OVERLAP * opts.length);
  PetscFunctionReturn(0);
}

PetscErrorCode MortarCoupling::BuildInterface(const Mesh &mesh, const ContactOptions &opts,
                                              const std::vector<char> &fixed, PetscInt item, const double *u_local) {
  const auto &[slave, master] = opts.pairs[item];
  const std::string input = "-contact_pairs " + slave + ":" + master;
  std::vector<GatheredFace> sf, mf;
  std::vector<PetscInt> vertices;
  PetscFunctionBeginUser;
  PetscCall(GatherFaces(mesh, slave, input, u_local, sf));
  PetscCall(GatherFaces(mesh, master, input, u_local, mf));
  // The two sides on one body would be self-contact, which needs rows that see the body's own deformation.
  std::set<PetscInt> slave_bodies;
  for (const GatheredFace &f : sf) slave_bodies.insert(f.body[0]);
  for (const GatheredFace &f : mf)
    PetscCheck(!slave_bodies.count(f.body[0]), mesh.Comm(), PETSC_ERR_USER_INPUT,
               "%s: '%s' and '%s' are both on body %" PetscInt_FMT " (bodies: the connected cell groups of the mesh, "
               "numbered from 0 by their first cell); expected the facet groups of two different bodies (self-contact "
               "is not supported)", input.c_str(), slave.c_str(), master.c_str(), f.body[0]);
  PetscCall(mesh.GroupVertices(master, vertices, input));
  for (PetscInt v : vertices) master_vertex_[v] = 1;
  PetscCall(mesh.GroupVertices(slave, vertices, input));
  // The owned slave nodes by file number.
  std::unordered_map<PetscInt, PetscInt> owned;
  for (PetscInt v : vertices) {
    slave_[v] = 1;
    if (mesh.Owned(v)) owned[mesh.VertexOriginal(v)] = v;
  }
  // The integrals over the slave segments or facets that touch an owned node, and each node's tributary length or
  // area.
  Integrals in;
  std::map<PetscInt, double> tributary;
  std::vector<GatheredFace> mine;
  for (const GatheredFace &s : sf) {
    bool touches = false;
    for (int a = 0; a < s.n; ++a) touches = touches || owned.count(s.node[a]);
    if (touches) mine.push_back(s);
  }
  std::vector<std::vector<std::size_t>> hit;
  radius_ = opts.search_radius;
  SlaveIntegrals(dim_, mine, mf, opts.search_radius, compliance_, in, &tributary, tangent_ ? &hit : nullptr);
  std::unordered_map<PetscInt, std::pair<const double *, PetscInt>> master_x; // reference position, body
  for (const GatheredFace &f : mf)
    for (int a = 0; a < f.n; ++a) master_x[f.node[a]] = {f.X[a].data(), f.body[a]};
  for (const auto &[node, Dj] : in.D) {
    const auto it = owned.find(node);
    // A node whose overlap is a vanishing part of its tributary length has no row worth its conditioning.
    if (it == owned.end() || !(Dj > 1e-6 * tributary[node])) continue;
    const PetscInt v = it->second;
    Row row{v, facet_base_ + item, {0, 0, 0}, 0, Dj, {}, {}, {}, {}, {}};
    // The interface's normal (from the master into the slave body, InterfaceNormal; the obstacle's of a rigid
    // master): a node on a flat master has the rows a rigid plane gives it.
    const auto &n = in.normal[node];
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int d = 0; d < dim_; ++d) row.n[d] = n[d] / len;
    double free2 = 0;
    for (int k = 0; k < dim_; ++k)
      if (!fixed[v * dim_ + k]) free2 += row.n[k] * row.n[k];
    if (free2 < 1e-12) continue; // the supports hold the node along its normal (as for a rigid obstacle)
    // The gap is g0 + n . (u_j - sum_l w_jl u_l) with the row's coefficients: g0 from the reference positions makes
    // it the weighted gap of the configuration the row was computed in (svk: the current one).
    row.g0 = 0;
    for (int d = 0; d < dim_; ++d) row.g0 += row.n[d] * mesh.X(v)[d];
    for (const auto &[l, Mjl] : in.M[node]) {
      const auto &[x, body] = master_x[l];
      MasterTerm t{l, Mjl / Dj, {x[0], x[1], x[2]}, body};
      for (int d = 0; d < dim_; ++d) row.g0 -= t.w * row.n[d] * x[d];
      row.terms.push_back(t);
    }
    if (tangent_) {
      // The row's own integrals, for Linearise: the slave facets around the node and the master facets they meet.
      std::set<std::size_t> masters;
      std::set<PetscInt> neighbours;
      std::vector<std::size_t> facets;
      for (std::size_t i = 0; i < mine.size(); ++i) {
        const GatheredFace &s = mine[i];
        if (std::find(s.node.begin(), s.node.begin() + s.n, node) == s.node.begin() + s.n) continue;
        row.near_slave.push_back(s);
        facets.push_back(i);
        masters.insert(hit[i].begin(), hit[i].end());
        for (int a = 0; a < s.n; ++a)
          if (s.node[a] != node) neighbours.insert(s.node[a]);
      }
      for (std::size_t m : masters) row.near_master.push_back(mf[m]);
      for (std::size_t i : facets) {
        row.near_hits.emplace_back();
        for (std::size_t m : hit[i]) row.near_hits.back().push_back((int)std::distance(masters.begin(), masters.find(m)));
      }
      row.neighbours.assign(neighbours.begin(), neighbours.end());
    }
    rows_.push_back(std::move(row));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode MortarCoupling::Update(const Mesh &mesh, const ContactOptions &opts, const std::vector<char> &fixed,
                                      const double *u_local, bool &changed) {
  PetscFunctionBeginUser;
  const auto pattern = [this] {
    std::vector<std::vector<PetscInt>> p;
    for (const Row &r : rows_) {
      p.push_back({r.vertex, r.facet});
      for (const MasterTerm &t : r.terms) p.back().push_back(t.node);
    }
    return p;
  };
  const auto before = pattern();
  PetscCall(Build(mesh, opts, fixed, facet_base_, u_local));
  changed = pattern() != before;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &changed, 1, MPI_CXX_BOOL, MPI_LOR, mesh.Comm()));
  PetscFunctionReturn(0);
}

void MortarCoupling::RefreshPairs(std::vector<ContactPair> &pairs) const {
  std::map<std::pair<PetscInt, PetscInt>, const Row *> index;
  for (const Row &r : rows_) index[{r.vertex, r.facet}] = &r;
  for (ContactPair &p : pairs) {
    const auto it = index.find({p.vertex, p.facet});
    if (it == index.end()) continue;
    std::copy(it->second->n, it->second->n + 3, p.n0);
    p.g0 = it->second->g0;
  }
}

void MortarCoupling::AppendPairs(const Mesh &mesh, std::vector<ContactPair> &pairs,
                                 std::vector<char> &candidate) const {
  for (const Row &r : rows_) {
    ContactPair p{r.vertex, r.facet, {r.n[0], r.n[1], r.n[2]}, r.g0, true, true, {0, 0, 0}};
    for (int k = 0; k < dim_; ++k) p.x0[k] = mesh.X(r.vertex)[k];
    pairs.push_back(p);
  }
  for (std::size_t v = 0; v < slave_.size(); ++v)
    if (slave_[v]) candidate[v] = 1;
}

PetscErrorCode MortarCoupling::Bind(const Mesh &mesh, const DofMap &dofs, const std::vector<char> &fixed,
                                    const std::vector<ContactPair> &pairs) {
  MPI_Comm comm = mesh.Comm();
  PetscFunctionBeginUser;
  // Each pair's row (pairs of one node are adjacent and sorted by facet).
  std::map<std::pair<PetscInt, PetscInt>, PetscInt> index;
  for (std::size_t r = 0; r < rows_.size(); ++r) index[{rows_[r].vertex, rows_[r].facet}] = (PetscInt)r;
  pair_row_.assign(pairs.size(), -1);
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const auto it = index.find({pairs[p].vertex, pairs[p].facet});
    if (it != index.end()) pair_row_[p] = it->second;
  }
  // The master nodes' first rows and fixed components, from their owners to every rank (the interfaces' nodes only).
  std::vector<PetscInt> needed;
  for (const Row &r : rows_) {
    for (const MasterTerm &t : r.terms) needed.push_back(t.node);
    needed.insert(needed.end(), r.neighbours.begin(), r.neighbours.end());
    for (const GatheredFace &f : r.near_master) needed.insert(needed.end(), f.node.begin(), f.node.begin() + f.n);
  }
  std::sort(needed.begin(), needed.end());
  needed.erase(std::unique(needed.begin(), needed.end()), needed.end());
  std::vector<PetscInt> all_needed;
  PetscCall(AllGatherUnion(comm, needed, all_needed));
  std::vector<PetscInt> info(2 * all_needed.size(), 0); // first row + 1 (0: not mine), fixed bits
  for (PetscInt v = 0; v < mesh.NumLocalVertices(); ++v) {
    if (!mesh.Owned(v)) continue;
    const auto it = std::lower_bound(all_needed.begin(), all_needed.end(), mesh.VertexOriginal(v));
    if (it == all_needed.end() || *it != mesh.VertexOriginal(v)) continue;
    const std::size_t i = it - all_needed.begin();
    info[2 * i] = dofs.Row(v, 0) + 1;
    for (int k = 0; k < dim_; ++k) info[2 * i + 1] |= fixed[v * dim_ + k] ? 1 << k : 0;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, info.data(), (int)info.size(), MPIU_INT, MPI_SUM, comm));
  master_.clear();
  for (std::size_t i = 0; i < all_needed.size(); ++i) master_[all_needed[i]] = {info[2 * i] - 1, (int)info[2 * i + 1]};
  // G: rows the owned pairs, columns the displacement rows of the whole system's layout, every component.
  const PetscInt start = dofs.RowStart(), end = start + dofs.OwnedRows();
  std::vector<PetscInt> d_nnz(pairs.size(), 0), o_nnz(pairs.size(), 0);
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    if (pair_row_[p] < 0) continue;
    for (const MasterTerm &t : rows_[pair_row_[p]].terms) {
      const PetscInt first = master_.at(t.node).first;
      ((first >= start && first < end) ? d_nnz : o_nnz)[p] += dim_;
    }
  }
  PetscCall(MatCreateAIJ(comm, (PetscInt)pairs.size(), dofs.OwnedRows(), PETSC_DETERMINE, PETSC_DETERMINE, 0,
                         d_nnz.data(), 0, o_nnz.data(), G_.out()));
  // W (friction only, KeepWeights): the weights per component, dim rows per pair with G's counts spread over them.
  PetscInt first_w = 0;
  if (weights_) {
    std::vector<PetscInt> wd_nnz(pairs.size() * dim_), wo_nnz(pairs.size() * dim_);
    for (std::size_t i = 0; i < wd_nnz.size(); ++i)
      wd_nnz[i] = d_nnz[i / dim_] / dim_, wo_nnz[i] = o_nnz[i / dim_] / dim_;
    PetscCall(MatCreateAIJ(comm, (PetscInt)pairs.size() * dim_, dofs.OwnedRows(), PETSC_DETERMINE, PETSC_DETERMINE,
                           0, wd_nnz.data(), 0, wo_nnz.data(), W_.out()));
    PetscCall(MatGetOwnershipRange(W_, &first_w, nullptr));
  }
  // G's entries, and each row's free master columns for the system (ExtendRows, at every evaluation of the pairs).
  PetscInt first_row;
  PetscCall(MatGetOwnershipRange(G_, &first_row, nullptr));
  free_columns_.assign(pairs.size(), {});
  free_terms_.assign(pairs.size(), {});
  neighbour_columns_.assign(pairs.size(), {});
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    if (pair_row_[p] < 0) continue;
    const Row &r = rows_[pair_row_[p]];
    for (PetscInt node : r.neighbours) {
      const auto &[first, fixed] = master_.at(node);
      for (int k = 0; k < dim_; ++k)
        if (!(fixed & (1 << k))) neighbour_columns_[p].push_back(first + k);
    }
    const PetscInt row = first_row + (PetscInt)p;
    for (const MasterTerm &t : r.terms) {
      const auto &[first, fixed] = master_.at(t.node);
      PetscInt cols[3];
      PetscScalar vals[3];
      for (int k = 0; k < dim_; ++k) {
        cols[k] = first + k, vals[k] = -t.w * r.n[k];
        if (!(fixed & (1 << k))) free_columns_[p].emplace_back(first + k, t.w * r.n[k]), free_terms_[p].push_back({t.w, k});
        if (weights_) PetscCall(MatSetValue(W_, first_w + (PetscInt)p * dim_ + k, first + k, t.w, ADD_VALUES));
      }
      PetscCall(MatSetValues(G_, 1, &row, dim_, cols, vals, ADD_VALUES));
    }
  }
  PetscCall(MatAssemblyBegin(G_, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(G_, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreateVecs(G_, x_.out(), y_.out()));
  if (!weights_) PetscFunctionReturn(0);
  PetscCall(MatAssemblyBegin(W_, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(W_, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreateVecs(W_, wx_.out(), wy_.out()));
  PetscFunctionReturn(0);
}

void MortarCoupling::MasterColumns(std::size_t p, const double *dir, double scale, SparseRow &row) const {
  if (p >= free_columns_.size()) return;
  for (std::size_t i = 0; i < free_columns_[p].size(); ++i)
    row.Add(free_columns_[p][i].first, scale * free_terms_[p][i].w * dir[free_terms_[p][i].k]);
}

PetscErrorCode MortarCoupling::Apply(Mat M, const Mesh &mesh, const DofMap &dofs, const double *u_local, Vec x,
                                     Vec y) const {
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(x));
  PetscCall(VecGetArray(x, &a));
  for (PetscInt v = 0; v < mesh.NumLocalVertices(); ++v)
    if (mesh.Owned(v))
      for (int k = 0; k < dim_; ++k) a[dofs.LocalOffset(v, k)] = u_local[v * dim_ + k];
  PetscCall(VecRestoreArray(x, &a));
  PetscCall(MatMult(M, x, y));
  PetscFunctionReturn(0);
}

PetscErrorCode MortarCoupling::MasterDisplacements(const Mesh &mesh, const DofMap &dofs, const double *u_local,
                                                   std::vector<double> &m) const {
  const PetscScalar *y;
  PetscFunctionBeginUser;
  PetscCall(Apply(W_, mesh, dofs, u_local, wx_, wy_));
  PetscCall(VecGetArrayRead(wy_, &y));
  m.assign(y, y + pair_row_.size() * dim_);
  PetscCall(VecRestoreArrayRead(wy_, &y));
  PetscFunctionReturn(0);
}

PetscErrorCode MortarCoupling::AddMasterVectorForces(const std::vector<double> &F, double sign, double *out,
                                                     PetscInt n) const {
  PetscScalar *y;
  const PetscScalar *x;
  PetscFunctionBeginUser;
  PetscCall(VecGetArray(wy_, &y));
  for (std::size_t i = 0; i < pair_row_.size() * dim_; ++i) y[i] = F[i];
  PetscCall(VecRestoreArray(wy_, &y));
  PetscCall(MatMultTranspose(W_, wy_, wx_));
  PetscCall(VecGetArrayRead(wx_, &x));
  for (PetscInt i = 0; i < n; ++i) out[i] -= sign * x[i];
  PetscCall(VecRestoreArrayRead(wx_, &x));
  PetscFunctionReturn(0);
}

const std::vector<MortarCoupling::MasterTerm> *MortarCoupling::Terms(std::size_t p) const {
  return p < pair_row_.size() && pair_row_[p] >= 0 ? &rows_[pair_row_[p]].terms : nullptr;
}

void MortarCoupling::ExtendRows(std::vector<ConstraintRow> &rows) const {
  for (std::size_t p = 0; p < rows.size() && p < free_columns_.size(); ++p)
  {
    for (const auto &[col, coef] : free_columns_[p]) rows[p].Add(col, coef);
    if (p < neighbour_columns_.size())
      for (PetscInt col : neighbour_columns_[p]) rows[p].Add(col, 0.0);
  }
}

PetscErrorCode MortarCoupling::AddMasterGaps(const Mesh &mesh, const DofMap &dofs, const double *u_local,
                                             std::vector<PairState> &states) const {
  const PetscScalar *y;
  PetscFunctionBeginUser;
  PetscCall(Apply(G_, mesh, dofs, u_local, x_, y_));
  PetscCall(VecGetArrayRead(y_, &y));
  for (std::size_t p = 0; p < states.size(); ++p)
    if (pair_row_[p] >= 0) states[p].gap += y[p];
  PetscCall(VecRestoreArrayRead(y_, &y));
  PetscFunctionReturn(0);
}

PetscErrorCode MortarCoupling::AddMasterForces(const std::vector<double> &lambda, double sign,
                                               std::vector<double> &out) const {
  PetscScalar *y;
  const PetscScalar *x;
  PetscFunctionBeginUser;
  PetscCall(VecGetArray(y_, &y));
  for (std::size_t p = 0; p < pair_row_.size(); ++p) y[p] = lambda[p];
  PetscCall(VecRestoreArray(y_, &y));
  PetscCall(MatMultTranspose(G_, y_, x_));
  PetscCall(VecGetArrayRead(x_, &x));
  for (std::size_t i = 0; i < out.size(); ++i) out[i] += sign * x[i];
  PetscCall(VecRestoreArrayRead(x_, &x));
  PetscFunctionReturn(0);
}

PetscErrorCode MortarCoupling::MasterForces(const Mesh &mesh, const DofMap &dofs, const std::vector<double> &lambda,
                                            std::vector<double> &master, double *sum) const {
  PetscFunctionBeginUser;
  master.assign(dofs.OwnedU(), 0.0);
  PetscCall(AddMasterForces(lambda, 1, master));
  for (PetscInt v = 0; v < mesh.NumLocalVertices(); ++v)
    if (mesh.Owned(v))
      for (int k = 0; k < dim_; ++k) sum[k] += master[dofs.LocalOffset(v, k)];
  PetscFunctionReturn(0);
}

PetscErrorCode MortarCoupling::Linearise(const Mesh &mesh, const DofMap &dofs, const std::vector<char> &fixed,
                                         const std::vector<double> &lambda, const std::vector<char> &active, Mat K,
                                         bool block, std::vector<ConstraintRow> &rows,
                                         std::vector<std::vector<double>> &columns) const {
  const int dim = dim_;
  PetscFunctionBeginUser;
  PetscCall(RegisterEvents());
  PetscCall(PetscLogEventBegin(EV_TANGENT, 0, 0, 0, 0));
  columns.assign(rows.size(), {});
  std::vector<PetscInt> nodes, cols, kcols;
  std::vector<double> x, c0, cp, cm, dc, dg, vals;
  for (std::size_t p = 0; p < rows.size() && p < pair_row_.size(); ++p) {
    if (pair_row_[p] < 0 || !(active[p] || lambda[p] != 0)) continue;
    const Row &r = rows_[pair_row_[p]];
    if (r.near_slave.empty()) continue;
    // The row's nodes: the slave node, its neighbours on the slave facets around it, the master facets' nodes; their
    // positions and free columns (-1: a Dirichlet dof).
    const PetscInt j = mesh.VertexOriginal(r.vertex);
    nodes.assign(1, j);
    nodes.insert(nodes.end(), r.neighbours.begin(), r.neighbours.end());
    for (const Facet &f : r.near_master)
      for (int a = 0; a < f.n; ++a)
        if (std::find(nodes.begin(), nodes.end(), f.node[a]) == nodes.end()) nodes.push_back(f.node[a]);
    const std::size_t n = nodes.size() * dim;
    x.assign(n, 0.0);
    cols.assign(n, -1);
    double length = 0;
    for (const std::vector<Facet> *side : {&r.near_slave, &r.near_master})
      for (const Facet &f : *side)
        for (int a = 0; a < f.n; ++a) {
          const std::size_t i = std::find(nodes.begin(), nodes.end(), f.node[a]) - nodes.begin();
          for (int k = 0; k < dim; ++k) x[i * dim + k] = f.x[a][k];
          if (side == &r.near_slave)
            for (int k = 0; k < dim; ++k) length = std::max(length, std::abs(f.x[(a + 1) % f.n][k] - f.x[a][k]));
        }
    for (std::size_t i = 0; i < nodes.size(); ++i)
      for (int k = 0; k < dim; ++k) {
        if (i == 0) {
          if (!fixed[r.vertex * dim + k]) cols[k] = dofs.Row(r.vertex, k);
          continue;
        }
        const auto &[first, bits] = master_.at(nodes[i]);
        if (!(bits & (1 << k))) cols[i * dim + k] = first + k;
      }
    // Central differences of the row's integrals over its own facets: a step of 1e-6 of the slave facets' size
    // (truncation ~1e-12, round-off ~1e-10 relative for coordinates up to 1e3 facet sizes from the origin). A node's
    // step changes only the shares of the slave facets that hold it or whose master facets do: the others' shares
    // are summed from the unperturbed ones.
    const double h = 1e-6 * length;
    const std::size_t nf = r.near_slave.size();
    std::vector<std::vector<Facet>> masters_of(nf);
    std::vector<RowSums> share(nf);
    RowSums sums;
    double g0, gp, gm;
    for (std::size_t i = 0; i < nf; ++i) {
      for (int m : r.near_hits[i]) masters_of[i].push_back(r.near_master[m]);
      share[i] = FacetShare(dim, j, r.near_slave[i], masters_of[i], radius_, compliance_);
      sums.Add(share[i]);
    }
    if (!RowOf(dim, j, sums, nodes, x, c0, g0)) continue;
    dc.assign(n * n, 0.0); // dc[e * n + b]: d c_e / d x_b
    dg.assign(n, 0.0);
    bool ok = true;
    const auto holds = [](const Facet &f, PetscInt node) {
      return std::find(f.node.begin(), f.node.begin() + f.n, node) != f.node.begin() + f.n;
    };
    for (std::size_t b = 0; b < n && ok; ++b) {
      if (cols[b] < 0) continue;
      const PetscInt node = nodes[b / dim];
      for (const double step : {h, -h}) {
        const auto shift = [&](Facet &f) {
          for (int a = 0; a < f.n; ++a)
            if (f.node[a] == node) f.x[a][b % dim] += step;
        };
        RowSums moved;
        for (std::size_t i = 0; i < nf; ++i) {
          bool touched = holds(r.near_slave[i], node);
          for (const Facet &m : masters_of[i]) touched = touched || holds(m, node);
          if (!touched) {
            moved.Add(share[i]);
            continue;
          }
          Facet S = r.near_slave[i];
          std::vector<Facet> M = masters_of[i];
          shift(S);
          for (Facet &f : M) shift(f);
          moved.Add(FacetShare(dim, j, S, M, radius_, compliance_));
        }
        std::vector<double> xs = x;
        xs[b] += step;
        ok = ok && RowOf(dim, j, moved, nodes, xs, step > 0 ? cp : cm, step > 0 ? gp : gm);
      }
      for (std::size_t e = 0; e < n; ++e) dc[e * n + b] = (cp[e] - cm[e]) / (2 * h);
      dg[b] = (gp - gm) / (2 * h);
    }
    if (!ok) continue; // a row that a step of 1e-6 of a facet makes or unmakes keeps its frozen tangent
    // lambda_p dc/du into K: rows the coefficients' free dofs, columns every free dof of the row.
    if (lambda[p] != 0) {
      kcols.clear();
      for (std::size_t b = 0; b < n; ++b)
        if (cols[b] >= 0) kcols.push_back(block ? dofs.UBlockRow(cols[b]) : cols[b]);
      for (std::size_t e = 0; e < n; ++e) {
        if (cols[e] < 0) continue;
        vals.clear();
        bool any = false;
        for (std::size_t b = 0; b < n; ++b)
          if (cols[b] >= 0) vals.push_back(lambda[p] * dc[e * n + b]), any = any || dc[e * n + b] != 0;
        if (!any) continue;
        const PetscInt row = block ? dofs.UBlockRow(cols[e]) : cols[e];
        PetscCall(MatSetValues(K, 1, &row, (PetscInt)kcols.size(), kcols.data(), vals.data(), ADD_VALUES));
      }
    }
    // The active row: the linearised weighted gap, -dg/du (the row of B is -grad g), its column the frozen one.
    if (active[p]) {
      columns[p] = rows[p].coef;
      for (PetscInt i = 0; i < rows[p].ncols; ++i) {
        const std::size_t b = std::find(cols.begin(), cols.end(), rows[p].cols[i]) - cols.begin();
        if (b < n) rows[p].coef[i] = -dg[b];
      }
    }
  }
  PetscCall(PetscLogEventEnd(EV_TANGENT, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace signorini
