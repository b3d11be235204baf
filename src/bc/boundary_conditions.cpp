// Parsing of the boundary-condition and load options.
#include "signorini/bc/boundary_conditions.hpp"
#include "signorini/core/handle.hpp"

#include "signorini/options/readers.hpp"
#include "signorini/core/parse.hpp"

#include <cmath>


namespace signorini {

std::string ParseDirichlet(const std::string &entry, int dim, std::vector<DirichletSpec> &out) {
  const auto fields = Split(entry, ':');
  if (fields.size() < 2 || fields[0].empty())
    return "'" + entry + "' is malformed; expected GROUP:COMPONENT[=VALUE][:COMPONENT[=VALUE]] such as left:x=0:y=0";
  for (std::size_t k = 1; k < fields.size(); ++k) {
    const auto eq = fields[k].find('=');
    const std::string comps = fields[k].substr(0, eq);
    double value = 0;
    if (eq != std::string::npos) {
      const auto v = ParseFinite(fields[k].substr(eq + 1));
      if (!v) return "'" + entry + "' has value '" + fields[k].substr(eq + 1) + "'; expected a finite number";
      value = *v;
    }
    if (comps.empty()) return "'" + entry + "' has an empty component; expected x, y" + (dim == 3 ? ", z" : "");
    for (char c : comps) {
      const int comp = c == 'x' ? 0 : c == 'y' ? 1 : c == 'z' ? 2 : -1;
      if (comp < 0 || comp >= dim)
        return "'" + entry + "' has component '" + std::string(1, c) + "'; expected " +
               (dim == 3 ? "x, y or z" : "x or y (the mesh is 2D)");
      out.push_back({fields[0], comp, value, entry});
    }
  }
  return "";
}

std::string ParseLoad(const std::string &entry, int count, const char *what, LoadSpec &out) {
  const auto fields = Split(entry, ':');
  const std::string form = count == 1 ? "GROUP:VALUE" : count == 2 ? "GROUP:VX:VY" : "GROUP:VX:VY:VZ";
  if (fields.size() < 2 || fields[0].empty())
    return std::string(what) + " '" + entry + "' is malformed; expected " + form;
  if ((int)fields.size() - 1 != count)
    return std::string(what) + " '" + entry + "' has " + std::to_string(fields.size() - 1) + " value(s); expected " +
           std::to_string(count) + " (" + form + ")";
  out.group = fields[0];
  out.item = entry;
  out.value.clear();
  for (std::size_t k = 1; k < fields.size(); ++k) {
    const auto v = ParseFinite(fields[k]);
    if (!v) return std::string(what) + " '" + entry + "' has value '" + fields[k] + "'; expected a finite number";
    out.value.push_back(*v);
  }
  return "";
}

PetscErrorCode ReadBoundaryConditions(MPI_Comm comm, int dim, BoundaryConditions &bc) {
  std::vector<std::string> dirichlet, traction, pressure, point_force;
  std::vector<double> body;
  PetscBool body_set = PETSC_FALSE;
  const char *nothing = "no condition of this kind";
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Boundary conditions and loads", "signorini");
  const OptionsBlockGuard options_block(PetscOptionsObject); // ends the block on an error
  PetscCall(OptionsStringList(PetscOptionsObject, "-bc_dirichlet", "Prescribed displacements GROUP:x=VALUE:y=VALUE"
                              "[:z=VALUE],... (value defaults to 0)", nothing, "GROUP:COMPONENT[=VALUE] items",
                              dirichlet));
  PetscCall(OptionsStringList(PetscOptionsObject, "-bc_traction", "Tractions GROUP:TX:TY[:TZ],... on physical curves "
                              "(2D) or surfaces (3D) (force per area)", nothing, "GROUP:TX:TY[:TZ] items", traction));
  PetscCall(OptionsStringList(PetscOptionsObject, "-bc_pressure", "Pressures GROUP:P,... on physical curves (2D) or "
                              "surfaces (3D), along the inward normal", nothing, "GROUP:P items", pressure));
  PetscCall(OptionsStringList(PetscOptionsObject, "-bc_point_force", "Point forces GROUP:FX:FY[:FZ],... on every node "
                              "of the group", nothing, "GROUP:FX:FY[:FZ] items", point_force));
  PetscCall(OptionsRealList(PetscOptionsObject, "-bc_body_force", "Body force per unit volume BX,BY[,BZ]", nothing,
                            "BX,BY[,BZ]", body, &body_set));
  PetscOptionsEnd();
  // -help lists the options before the mesh, and so its dimension, is known (dim 0): nothing to parse.
  if (dim == 0) PetscFunctionReturn(0);

  bc = BoundaryConditions{};
  std::string error;
  for (const auto &e : dirichlet)
    if (error.empty()) {
      error = ParseDirichlet(e, dim, bc.dirichlet);
      if (!error.empty()) error = "-bc_dirichlet " + error;
    }
  const struct {
    const std::vector<std::string> &entries;
    std::vector<LoadSpec> &out;
    int count;
    const char *what;
  } loads[] = {{traction, bc.traction, dim, "-bc_traction"},
               {pressure, bc.pressure, 1, "-bc_pressure"},
               {point_force, bc.point_force, dim, "-bc_point_force"}};
  for (const auto &l : loads)
    for (const auto &e : l.entries) {
      LoadSpec spec;
      if (error.empty()) error = ParseLoad(e, l.count, l.what, spec);
      l.out.push_back(spec);
    }
  PetscCheck(error.empty(), comm, PETSC_ERR_USER_INPUT, "%s", error.c_str());
  if (body_set) {
    PetscCheck((int)body.size() == dim, comm, PETSC_ERR_USER_INPUT,
               "-bc_body_force has %zu value(s); expected %d (%s)", body.size(), dim, dim == 2 ? "BX,BY" : "BX,BY,BZ");
    bc.body_force = body;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode CheckLoadScale(MPI_Comm comm, const BoundaryConditions &bc, double L, double E, double t) {
  struct Limit {
    const char *option;
    std::string group;
    double value, limit;
    const char *scale;
  };
  std::vector<Limit> limits;
  const struct {
    const char *option;
    const std::vector<LoadSpec> &loads;
    double limit;
    const char *scale;
  } kinds[] = {{"-bc_traction", bc.traction, E, "E"},
               {"-bc_pressure", bc.pressure, E, "E"},
               {"-bc_point_force", bc.point_force, E * t * L, "E x thickness x body diagonal"}};
  for (const auto &k : kinds)
    for (const auto &l : k.loads)
      for (double v : l.value) limits.push_back({k.option, "group '" + l.group + "' ", v, k.limit, k.scale});
  for (double v : bc.body_force) limits.push_back({"-bc_body_force", "", v, E / L, "E / body diagonal"});
  for (const auto &d : bc.dirichlet)
    limits.push_back({"-bc_dirichlet", "group '" + d.group + "' ", d.value, L, "body diagonal"});
  PetscFunctionBeginUser;
  for (const auto &l : limits)
    PetscCheck(std::abs(l.value) <= LOAD_SCALE_MAX * l.limit, comm, PETSC_ERR_USER_INPUT,
               "%s %svalue %s is out of scale with the problem; expected |value| <= %s (%s x %s, %s = %s), beyond "
               "which the discrete system overflows", l.option, l.group.c_str(), FormatNumber(l.value).c_str(),
               FormatNumber(LOAD_SCALE_MAX * l.limit).c_str(), FormatNumber(LOAD_SCALE_MAX).c_str(), l.scale, l.scale,
               FormatNumber(l.limit).c_str());
  PetscFunctionReturn(0);
}

} // namespace signorini
