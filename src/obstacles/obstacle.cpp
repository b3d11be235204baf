// The registry of obstacle shapes and the reading of the -obstacle_ options.
#include "signorini/obstacles/obstacle.hpp"
#include "signorini/core/handle.hpp"

#include "signorini/options/option_paths.hpp"
#include "signorini/options/readers.hpp"
#include "signorini/core/parse.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace signorini {

const std::vector<ShapeType> &ShapeRegistry() {
  static const std::vector<ShapeType> registry = {SegmentsShape(), ArcsShape(),     DiscsShape(),
                                                  PlanesShape(),   SpheresShape(), CylindersShape(),
                                                  RectanglesShape()};
  return registry;
}

void TangentFrame(const double *n, double *t1, double *t2) {
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(n[i]) < std::abs(n[k])) k = i;
  // t1 = n x e_k, normalised; t2 = n x t1.
  const double e[3] = {k == 0 ? 1.0 : 0.0, k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0};
  t1[0] = n[1] * e[2] - n[2] * e[1], t1[1] = n[2] * e[0] - n[0] * e[2], t1[2] = n[0] * e[1] - n[1] * e[0];
  const double norm = std::sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
  for (int i = 0; i < 3; ++i) t1[i] /= norm;
  t2[0] = n[1] * t1[2] - n[2] * t1[1], t2[1] = n[2] * t1[0] - n[0] * t1[2], t2[2] = n[0] * t1[1] - n[1] * t1[0];
}

void BoxExtent(const Box &box, const double *origin, const double *d, double &lo, double &hi) {
  lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (int corner = 0; corner < 8; ++corner) {
    double t = 0;
    for (int i = 0; i < 3; ++i) t += d[i] * ((corner >> i & 1 ? box.hi[i] : box.lo[i]) - origin[i]);
    lo = std::min(lo, t), hi = std::max(hi, t);
  }
}

void AppendTriangle(TriangleSoup &out, const std::array<double, 3> &a, const std::array<double, 3> &b,
                    const std::array<double, 3> &c, const double *into) {
  const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  const bool along = n[0] * into[0] + n[1] * into[1] + n[2] * into[2] >= 0;
  out.insert(out.end(), {a, along ? b : c, along ? c : b});
}

std::vector<std::string> ObstacleKinds() {
  std::vector<std::string> kinds;
  for (const ShapeType &shape : ShapeRegistry()) kinds.push_back(std::string(shape.option).substr(10)); // "-obstacle_"
  kinds.push_back("mesh");
  return kinds;
}

int ShapeKind(const ShapeType &shape) { return (int)(&shape - ShapeRegistry().data()); }

int MeshKind() { return (int)ShapeRegistry().size(); }

namespace {

/// -obstacle_friction's items KIND:MU into obstacle.kind_friction: known kinds that the run has, each once, MU a
/// number in [0, 1000].
PetscErrorCode ParseKindFriction(MPI_Comm comm, const std::vector<std::string> &items, Obstacle &obstacle) {
  PetscFunctionBeginUser;
  const std::vector<std::string> kinds = ObstacleKinds();
  obstacle.kind_friction.assign(kinds.size(), -1.0);
  obstacle.friction_option = Join(items, ",");
  std::vector<std::string> given;
  for (const ShapeType *shape : obstacle.shapes) given.push_back(kinds[ShapeKind(*shape)]);
  if (!obstacle.meshes.empty()) given.push_back(kinds[MeshKind()]);
  for (const std::string &item : items) {
    const std::size_t colon = item.find(':');
    const std::string kind = item.substr(0, colon), text = colon == std::string::npos ? "" : item.substr(colon + 1);
    const auto k = std::find(kinds.begin(), kinds.end(), kind);
    PetscCheck(colon != std::string::npos && k != kinds.end(), comm, PETSC_ERR_USER_INPUT,
               "-obstacle_friction: item '%s' is not of the form KIND:MU; expected a kind of obstacle (%s) and its "
               "friction coefficient, e.g. -obstacle_friction planes:0.2", item.c_str(), Join(kinds, ", ").c_str());
    PetscCheck(std::find(given.begin(), given.end(), kind) != given.end(), comm, PETSC_ERR_USER_INPUT,
               "-obstacle_friction: item '%s' names obstacles of kind %s, which the run has none of; expected one of "
               "the run's kinds (%s)", item.c_str(), kind.c_str(),
               given.empty() ? "none: no -obstacle_ option" : Join(given, ", ").c_str());
    const std::optional<double> mu = ParseFinite(text);
    PetscCheck(mu && *mu >= 0 && *mu <= 1e3, comm, PETSC_ERR_USER_INPUT,
               "-obstacle_friction: item '%s' has the friction coefficient '%s'; expected a number in [0, 1000]",
               item.c_str(), text.c_str());
    double &slot = obstacle.kind_friction[k - kinds.begin()];
    PetscCheck(slot < 0, comm, PETSC_ERR_USER_INPUT,
               "-obstacle_friction: kind %s is given twice; expected each kind once", kind.c_str());
    slot = *mu;
  }
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode ReadObstacle(MPI_Comm comm, Obstacle &obstacle) {
  std::vector<double> values;
  PetscFunctionBeginUser;
  obstacle.facets.clear();
  obstacle.facet_kind.clear();
  std::vector<std::string> friction;
  obstacle.shapes.clear();
  obstacle.meshes.clear();
  std::vector<std::string> meshes;
  PetscOptionsBegin(comm, nullptr, "Rigid obstacle", "signorini");
  const OptionsBlockGuard options_block(PetscOptionsObject); // ends the block on an error
  for (const ShapeType &shape : ShapeRegistry()) {
    PetscBool set = PETSC_FALSE;
    PetscCall(OptionsRealList(PetscOptionsObject, shape.option, shape.help, "no obstacle of this shape",
                              (std::to_string(shape.numbers) + " numbers per item").c_str(), values, &set));
    if (!set) continue;
    obstacle.shapes.push_back(&shape);
    const std::size_t n = values.size(), numbers = shape.numbers;
    PetscCheck(n % numbers == 0, comm, PETSC_ERR_USER_INPUT, "%s has %zu number(s); expected a multiple of %zu",
               shape.option, n, numbers);
    for (std::size_t k = 0; k < n / numbers; ++k) {
      const std::string error = shape.build(&values[k * numbers], obstacle.facets);
      PetscCheck(error.empty(), comm, PETSC_ERR_USER_INPUT, "%s item %zu %s", shape.option, k + 1, error.c_str());
    }
    obstacle.facet_kind.resize(obstacle.facets.size(), ShapeKind(shape));
  }
  PetscCall(OptionsStringList(PetscOptionsObject, "-obstacle_mesh", "Meshed rigid surfaces FILE[:GROUP],... from gmsh "
                              "files (.msh, .geo): 2-node lines for a 2D body, triangles and quadrilaterals for a 3D "
                              "one, of the physical group GROUP (default: all); the node order orients each facet (left "
                              "normal of P0->P1; right-hand rule) into the body", "no meshed obstacle",
                              "FILE or FILE:GROUP items", meshes));
  PetscCall(OptionsStringList(PetscOptionsObject, "-obstacle_friction", "Coulomb friction coefficient per kind of "
                              "obstacle, KIND:MU,... (KIND: segments, arcs, discs, planes, spheres, cylinders, "
                              "rectangles or mesh; the kinds not given take -contact_friction)",
                              "-contact_friction on every obstacle", "KIND:MU items", friction));
  PetscOptionsEnd();
  for (const std::string &item : meshes) {
    ObstacleMeshSource source;
    source.value = item;
    // FILE:GROUP splits at the last colon that is followed by no path separator.
    const std::size_t colon = item.rfind(':');
    const bool grouped = colon != std::string::npos && item.find('/', colon) == std::string::npos;
    source.file = grouped ? item.substr(0, colon) : item;
    source.group = grouped ? item.substr(colon + 1) : "";
    PetscCheck(!source.file.empty() && !(grouped && source.group.empty()), comm, PETSC_ERR_USER_INPUT,
               "-obstacle_mesh item '%s' has an empty %s; expected FILE or FILE:GROUP", item.c_str(),
               source.file.empty() ? "file name" : "group name");
    PathCandidates candidates;
    PetscCall(PathCandidatesFor("-obstacle_mesh", source.file, candidates));
    source.paths = candidates.paths;
    source.origins = candidates.origins;
    obstacle.meshes.push_back(source);
  }
  PetscCall(ParseKindFriction(comm, friction, obstacle));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckObstacleDimension(MPI_Comm comm, const Obstacle &obstacle, int dim) {
  PetscFunctionBeginUser;
  std::vector<std::string> fitting;
  for (const ShapeType &shape : ShapeRegistry())
    if (shape.dim == dim) fitting.push_back(shape.option);
  fitting.push_back("-obstacle_mesh");
  for (const ShapeType *shape : obstacle.shapes)
    PetscCheck(shape->dim == dim, comm, PETSC_ERR_USER_INPUT,
               "%s is a %dD shape but the mesh is %dD; expected %s", shape->option, shape->dim, dim,
               Join(fitting, ", ").c_str());
  PetscFunctionReturn(0);
}

} // namespace signorini
