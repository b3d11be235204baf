// Parsing of the boundary-condition and load options.
#include "signorini/bc/boundary_conditions.hpp"
#include "signorini/core/handle.hpp"

#include "signorini/options/readers.hpp"
#include "signorini/core/parse.hpp"

#include <cmath>
#include <optional>


namespace signorini {

namespace {

constexpr const char *RAMP_GRAMMAR = "expected one suffix @T0:T1 with numbers 0 <= T0 < T1 <= 1 (the load steps' "
                                     "pseudo-time)";

} // namespace

std::string Ramp::Suffix() const {
  return Proportional() ? "" : "@" + FormatNumber(t0) + ":" + FormatNumber(t1);
}

std::string ParseRamp(const std::string &entry, std::string &rest, Ramp &ramp) {
  const auto at = entry.find('@');
  ramp = Ramp{};
  rest = entry.substr(0, at);
  if (at == std::string::npos) return "";
  const std::string text = entry.substr(at);
  const auto quote = "'" + entry + "' has ramp '" + text + "'";
  if (entry.find('@', at + 1) != std::string::npos) return "'" + entry + "' has two ramps; " + RAMP_GRAMMAR;
  const auto fields = Split(text.substr(1), ':');
  if (text.size() == 1) return "'" + entry + "' has an empty ramp '@'; " + RAMP_GRAMMAR;
  std::optional<double> t0, t1;
  if (fields.size() == 2) t0 = ParseFinite(fields[0]), t1 = ParseFinite(fields[1]);
  if (!t0 || !t1) return quote + ", not two numbers T0:T1; " + RAMP_GRAMMAR;
  if (*t0 < 0 || *t1 > 1) return quote + " outside [0, 1]; " + RAMP_GRAMMAR;
  if (*t0 >= *t1) return quote + ", which does not start before it ends; " + RAMP_GRAMMAR;
  ramp = Ramp{*t0, *t1};
  return "";
}

std::string ParseDirichlet(const std::string &entry, int dim, std::vector<DirichletSpec> &out) {
  std::string body;
  Ramp ramp;
  if (std::string error = ParseRamp(entry, body, ramp); !error.empty()) return error;
  const auto fields = Split(body, ':');
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
      out.push_back({fields[0], comp, value, entry, ramp});
    }
  }
  return "";
}

std::string ParseLoad(const std::string &entry, int count, const char *what, LoadSpec &out) {
  std::string body;
  if (std::string error = ParseRamp(entry, body, out.ramp); !error.empty()) return std::string(what) + " " + error;
  const auto fields = Split(body, ':');
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

bool AnyRampMoves(const BoundaryConditions &bc, double t0, double t1) {
  const auto moves = [t0, t1](const Ramp &r, const std::vector<double> &value) {
    return r.At(t0) != r.At(t1) && std::any_of(value.begin(), value.end(), [](double v) { return v != 0; });
  };
  for (const auto &d : bc.dirichlet)
    if (moves(d.ramp, {d.value})) return true;
  for (const auto *loads : {&bc.traction, &bc.pressure, &bc.point_force})
    for (const auto &l : *loads)
      if (moves(l.ramp, l.value)) return true;
  return moves(bc.body_force_ramp, bc.body_force);
}

PetscErrorCode ReadBoundaryConditions(MPI_Comm comm, int dim, BoundaryConditions &bc) {
  std::vector<std::string> dirichlet, traction, pressure, point_force, body;
  PetscBool body_set = PETSC_FALSE;
  const char *nothing = "no condition of this kind";
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Boundary conditions and loads", "signorini");
  const OptionsBlockGuard options_block(PetscOptionsObject); // ends the block on an error
  PetscCall(OptionsStringList(PetscOptionsObject, "-bc_dirichlet", "Prescribed displacements GROUP:x=VALUE:y=VALUE"
                              "[:z=VALUE][@T0:T1],... (value defaults to 0). Every -bc_ item may end with a ramp @T0:T1 "
                              "(0 <= T0 < T1 <= 1): it is applied from pseudo-time T0 to T1 of the load steps "
                              "(top:5@0:0.5: over the first half of -load_steps); without one, in proportion over all "
                              "of them", nothing, "GROUP:COMPONENT[=VALUE][@T0:T1] items", dirichlet));
  PetscCall(OptionsStringList(PetscOptionsObject, "-bc_traction", "Tractions GROUP:TX:TY[:TZ][@T0:T1],... on physical "
                              "curves (2D) or surfaces (3D) (force per area)", nothing,
                              "GROUP:TX:TY[:TZ][@T0:T1] items", traction));
  PetscCall(OptionsStringList(PetscOptionsObject, "-bc_pressure", "Pressures GROUP:P[@T0:T1],... on physical curves "
                              "(2D) or surfaces (3D), along the inward normal", nothing, "GROUP:P[@T0:T1] items",
                              pressure));
  PetscCall(OptionsStringList(PetscOptionsObject, "-bc_point_force", "Point forces GROUP:FX:FY[:FZ][@T0:T1],... on "
                              "every node of the group", nothing, "GROUP:FX:FY[:FZ][@T0:T1] items", point_force));
  PetscCall(OptionsStringList(PetscOptionsObject, "-bc_body_force", "Body force per unit volume BX,BY[,BZ][@T0:T1]",
                              nothing, "BX,BY[,BZ][@T0:T1]", body, &body_set));
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
    // The ramp follows the last number: the whole value is the entry.
    const std::string text = Join(body, ",");
    std::string numbers;
    error = ParseRamp(text, numbers, bc.body_force_ramp);
    PetscCheck(error.empty(), comm, PETSC_ERR_USER_INPUT, "-bc_body_force %s", error.c_str());
    PetscCall(ParseRealList(comm, "-bc_body_force", text, Split(numbers, ','), bc.body_force));
    PetscCheck((int)bc.body_force.size() == dim, comm, PETSC_ERR_USER_INPUT,
               "-bc_body_force has %zu value(s); expected %d (%s)", bc.body_force.size(), dim,
               dim == 2 ? "BX,BY" : "BX,BY,BZ");
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
