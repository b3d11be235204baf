// Parsing of the boundary-condition and load options.
#include "signorini/bc/boundary_conditions.hpp"

#include "signorini/core/parse.hpp"

#include <cmath>

namespace signorini {

namespace {

constexpr PetscInt MAX_ENTRIES = 256;

PetscErrorCode ReadEntries(PetscOptionItems *PetscOptionsObject, const char *name, const char *help, std::vector<std::string> &entries) {
  char *values[MAX_ENTRIES];
  PetscInt n = MAX_ENTRIES;
  PetscBool set = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsStringArray(name, help, "", values, &n, &set));
  entries.clear();
  if (set)
    for (PetscInt i = 0; i < n; ++i) {
      entries.emplace_back(values[i]);
      PetscCall(PetscFree(values[i]));
    }
  PetscFunctionReturn(0);
}

} // namespace

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
      out.push_back({fields[0], comp, value});
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
  PetscReal body[MAX_ENTRIES];
  PetscInt nbody = MAX_ENTRIES;
  PetscBool body_set = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Boundary conditions and loads", "signorini");
  PetscCall(ReadEntries(PetscOptionsObject, "-bc_dirichlet", "Prescribed displacements GROUP:x=VALUE:y=VALUE,... (value defaults to 0)",
                        dirichlet));
  PetscCall(ReadEntries(PetscOptionsObject, "-bc_traction", "Tractions GROUP:TX:TY,... on physical curves (force per area)", traction));
  PetscCall(ReadEntries(PetscOptionsObject, "-bc_pressure", "Pressures GROUP:P,... on physical curves, along the inward normal", pressure));
  PetscCall(ReadEntries(PetscOptionsObject, "-bc_point_force", "Point forces GROUP:FX:FY,... on every node of the group", point_force));
  PetscCall(PetscOptionsRealArray("-bc_body_force", "Body force per unit volume BX,BY", "", body, &nbody, &body_set));
  PetscOptionsEnd();

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
    PetscCheck(nbody == dim, comm, PETSC_ERR_USER_INPUT,
               "-bc_body_force has %" PetscInt_FMT " value(s); expected %d (BX,BY)", nbody, dim);
    for (PetscInt i = 0; i < nbody; ++i)
      PetscCheck(std::isfinite(body[i]), comm, PETSC_ERR_USER_INPUT,
                 "-bc_body_force value %" PetscInt_FMT " is not finite; expected finite numbers", i);
    bc.body_force.assign(body, body + nbody);
  }
  PetscFunctionReturn(0);
}

} // namespace signorini
