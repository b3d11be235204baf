// Printed summary, summary.json and the Hertz comparison.
#include "signorini/post/report.hpp"
#include "signorini/core/handle.hpp"

#include "signorini/options/readers.hpp"
#include "signorini/io/json.hpp"
#include "signorini/core/parse.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <cstdio>
#include <vector>

namespace signorini {

PetscErrorCode ReadReportOptions(MPI_Comm comm, HertzReport &hertz) {
  std::vector<double> v;
  PetscBool set = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Report", "signorini");
  const OptionsBlockGuard options_block(PetscOptionsObject); // ends the block on an error
  PetscCall(OptionsRealList(PetscOptionsObject, "-report_hertz", "Compare with Hertz contact: 2D cylinder radius R and "
                            "load P per unit thickness, 3D sphere radius R and total load P (R,P); between two bodies "
                            "(-contact_pairs) R is the effective radius, 1 / R = 1 / R1 + 1 / R2", "no comparison",
                            "R,P", v, &set));
  PetscOptionsEnd();
  if (!set) PetscFunctionReturn(0);
  PetscCheck(v.size() == 2 && v[0] > 0 && v[1] > 0, comm, PETSC_ERR_USER_INPUT,
             "-report_hertz expects two positive numbers R,P (radius, load: per unit thickness in 2D, total in 3D)");
  hertz.enabled = true;
  hertz.R = v[0];
  hertz.P = v[1];
  PetscFunctionReturn(0);
}

namespace {

/// The contact centre: the candidate node of the first contact (the smallest initial gap; the smallest original
/// vertex number at a tie), its reference position and the normal of its pair, the same on every rank. Collective.
PetscErrorCode ContactCentre(const SolvedState &state, double centre[3], double normal[3]) {
  const Mesh &mesh = state.mesh;
  const auto &pairs = state.pairs;
  MPI_Comm comm = mesh.Comm();
  double g_local = std::numeric_limits<double>::infinity(), g_min;
  PetscFunctionBeginUser;
  for (const auto &p : pairs) g_local = std::min(g_local, p.g0);
  PetscCallMPI(MPI_Allreduce(&g_local, &g_min, 1, MPI_DOUBLE, MPI_MIN, comm));
  PetscInt id_local = PETSC_MAX_INT, id_min;
  std::size_t best = pairs.size();
  for (std::size_t p = 0; p < pairs.size(); ++p)
    if (pairs[p].g0 == g_min && mesh.VertexOriginal(pairs[p].vertex) < id_local) {
      id_local = mesh.VertexOriginal(pairs[p].vertex);
      best = p;
    }
  PetscCallMPI(MPI_Allreduce(&id_local, &id_min, 1, MPIU_INT, MPI_MIN, comm));
  double local[6] = {0, 0, 0, 0, 0, 0}, global[6];
  if (best < pairs.size() && id_local == id_min)
    for (int k = 0; k < mesh.Dim(); ++k) {
      local[k] = mesh.X(pairs[best].vertex)[k];
      local[3 + k] = pairs[best].n0[k];
    }
  PetscCallMPI(MPI_Allreduce(local, global, 6, MPI_DOUBLE, MPI_SUM, comm));
  for (int k = 0; k < 3; ++k) {
    centre[k] = global[k];
    normal[k] = global[3 + k];
  }
  PetscFunctionReturn(0);
}

/// The computed peak pressure p0_h, with a_fit and fit_nodes, from Hertz's profile fitted to the nodal pressures of
/// the active nodes (nodes) around the contact centre. Collective.
PetscErrorCode FitProfile(const SolvedState &state, const NodeContact &nodes, const ContactSummary &s, HertzReport &h) {
  PetscFunctionBeginUser;
  // Peak pressure: the nodal pressure lambda / w scatters by a few per cent from node to node on an unstructured
  // mesh, so its maximum overshoots p0 and the value at the centre undershoots it. Hertz's profile p^2 = p0^2 (1 -
  // r^2 / a^2) is linear in r^2: p0^2 is the intercept of the least-squares line through (r^2, p^2) of the active
  // nodes within HERTZ_FIT_RADIUS of the outermost active node's distance r_out from the centre (the nodes of the
  // outer ring average the pressure over the edge of the contact zone).
  constexpr double HERTZ_FIT_RADIUS = 0.8;
  const Mesh &mesh = state.mesh;
  const int dim = mesh.Dim();
  MPI_Comm comm = mesh.Comm();
  double centre[3], normal[3];
  PetscCall(ContactCentre(state, centre, normal));
  std::vector<double> r2(mesh.NumLocalVertices(), 0.0);
  double r2_out_local = 0, r2_out;
  for (PetscInt v = 0; v < mesh.NumLocalVertices(); ++v) {
    if (!mesh.Owned(v) || !nodes.active[v]) continue;
    double d2 = 0, dn = 0;
    for (int k = 0; k < dim; ++k) {
      const double d = mesh.X(v)[k] - centre[k];
      d2 += d * d;
      dn += d * normal[k];
    }
    r2[v] = std::max(0.0, d2 - dn * dn); // squared distance from the centre in the plane of the contact
    r2_out_local = std::max(r2_out_local, r2[v]);
  }
  PetscCallMPI(MPI_Allreduce(&r2_out_local, &r2_out, 1, MPI_DOUBLE, MPI_MAX, comm));
  double local[5] = {0, 0, 0, 0, 0}, sums[5]; // n, sum r^2, sum r^4, sum p^2, sum p^2 r^2
  for (PetscInt v = 0; v < mesh.NumLocalVertices(); ++v) {
    if (!mesh.Owned(v) || !nodes.active[v] || r2[v] > HERTZ_FIT_RADIUS * HERTZ_FIT_RADIUS * r2_out) continue;
    const double p2 = nodes.pressure[v] * nodes.pressure[v];
    local[0] += 1;
    local[1] += r2[v];
    local[2] += r2[v] * r2[v];
    local[3] += p2;
    local[4] += p2 * r2[v];
  }
  PetscCallMPI(MPI_Allreduce(local, sums, 5, MPI_DOUBLE, MPI_SUM, comm));
  const double det = sums[0] * sums[2] - sums[1] * sums[1];
  const double intercept = det > 0 ? (sums[2] * sums[3] - sums[1] * sums[4]) / det : 0;
  h.fit_nodes = (PetscInt)sums[0];
  h.p0_h = intercept > 0 ? std::sqrt(intercept) : s.max_pressure; // fewer than two distinct radii: the largest
  // The same line's slope is -p0^2 / a^2: a from the profile, which does not move by whole elements as the contact
  // length or area of the active nodes does (+-h/2: +0.71 % on the Hertz mesh of size factor 0.25, where the fit
  // gives +0.09 %).
  const double slope = det > 0 ? (sums[0] * sums[4] - sums[1] * sums[3]) / det : 0;
  h.a_fit = intercept > 0 && slope < 0 ? std::sqrt(-intercept / slope) : 0;
  PetscFunctionReturn(0);
}

} // namespace

/// The material of the cells that hold the nodes marked (per local vertex) in `marks` (the contact body's: the
/// candidate nodes; the master sides of pairs of bodies), in contact; count: how many distinct materials those cells
/// have over the ranks (1 with one material). Collective.
PetscErrorCode ContactMaterial(const SolvedState &state, const Material &m, const std::vector<char> &marks,
                               Material &contact, int &count) {
  const Mesh &mesh = state.mesh;
  PetscFunctionBeginUser;
  contact = m.With(m.E, m.nu);
  count = 1;
  if (m.constants.empty()) PetscFunctionReturn(0);
  std::vector<int> used(m.constants.size(), 0);
  for (PetscInt c = 0; c < mesh.NumLocalCells(); ++c) {
    PetscInt n;
    const PetscInt *cv = mesh.CellVertices(c, n);
    for (PetscInt a = 0; a < n; ++a)
      if (marks[cv[a]]) used[m.cell_constants[c]] = 1;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, used.data(), (int)used.size(), MPI_INT, MPI_MAX, mesh.Comm()));
  count = (int)std::count(used.begin(), used.end(), 1);
  const auto first = std::find(used.begin(), used.end(), 1) - used.begin();
  if (count == 1) contact = m.With(m.constants[first]);
  PetscFunctionReturn(0);
}

/// Hertz's theory is for contacts small against the radius; a / R beyond this is not a Hertz case (the Hertz meshes
/// have a / R = 0.085 in 2D and 0.08 in 3D).
constexpr double HERTZ_MAX_A_OVER_R = 0.5;

PetscErrorCode ComputeHertz(const SolvedState &state, const Material &material, const NodeContact &nodes,
                            const ContactSummary &s, HertzReport &h) {
  const Mesh &mesh = state.mesh;
  const int dim = mesh.Dim();
  MPI_Comm comm = mesh.Comm();
  Material m;
  PetscFunctionBeginUser;
  if (!h.enabled || s.active_nodes == 0) PetscFunctionReturn(0);
  h.dim = dim;
  // Johnson's E* is that of the body in contact: with materials per group, the one material of the cells along the
  // contact boundary, or no comparison. Between two bodies, 1 / E* = 1 / E*_slave + 1 / E*_master (Johnson 1985,
  // 4.2), each side's the one material of its cells.
  PetscCall(ContactMaterial(state, material, state.candidates, m, h.contact_materials));
  Material master = m;
  if (s.bodies) {
    int count;
    PetscCall(ContactMaterial(state, material, state.mortar->MasterVertices(), master, count));
    if (count != 1) h.contact_materials = std::max(h.contact_materials, 2);
  }
  if (h.contact_materials != 1) PetscFunctionReturn(0);
  // The model carries the fraction 1, 1/2 or 1/4 (one or two symmetry planes) of P: the power of two nearest to
  // |contact force| / P. Johnson's values are those of the load it carries, P_model = |contact force| / fraction
  // (a pressure on a faceted curved boundary falls short of the nominal load by the area the facets cut off).
  // In 2D P is per unit thickness, and the model's contact force that of its thickness. With friction P is the
  // normal part: the contact force less the friction force (Cattaneo and Mindlin's tangential load leaves Hertz's
  // normal solution as it is).
  std::array<double, 3> f;
  for (int k = 0; k < 3; ++k) f[k] = s.contact_force[k] - (s.friction ? s.friction_force[k] : 0.0);
  const double force = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]) / (dim == 2 ? m.thickness : 1.0);
  const int halvings = std::clamp((int)std::lround(std::log2(h.P / force)), 0, 2);
  h.fraction = std::ldexp(1.0, -halvings);
  h.P_model = force / h.fraction;
  // The faceted boundary of a coarse mesh carries a little less than the nominal load (0.98 of it in hertz3d.msh):
  // beyond HERTZ_LOAD_TOL the case is not the Hertz case of load P (another load, or no cylinder or sphere).
  constexpr double HERTZ_LOAD_TOL = 0.1;
  PetscCheck(!h.check_load || std::abs(h.P_model / h.P - 1) <= HERTZ_LOAD_TOL, comm, PETSC_ERR_USER_INPUT,
             "-report_hertz %.6g,%.6g: the contact force%s is %.6g, which is not P, P/2 or P/4 within %d %%; expected the "
             "load P of a Hertz case (a cylinder in 2D or a sphere in 3D on a flat, or its half or quarter by symmetry "
             "planes)", h.R, h.P, dim == 2 ? " per unit thickness" : "", force, (int)std::lround(100 * HERTZ_LOAD_TOL));
  // A body's part of E*: E / (1 - nu^2), E in plane stress; a rigid obstacle adds nothing.
  const auto part = [&](const Material &b) { return dim == 2 && b.plane_stress ? b.E : b.E / (1 - b.nu * b.nu); };
  const double Estar = s.bodies ? 1 / (1 / part(m) + 1 / part(master)) : part(m);
  if (dim == 2) {
    h.a = std::sqrt(4 * h.P_model * h.R / (M_PI * Estar));
    h.p0 = 2 * h.P_model / (M_PI * h.a);
    h.a_h = 0.5 * s.contact_length / h.fraction; // the length of the contact zone of the whole cylinder is 2 a
  } else {
    h.a = std::cbrt(3 * h.P_model * h.R / (4 * Estar));
    h.p0 = 3 * h.P_model / (2 * M_PI * h.a * h.a);
    h.a_h = std::sqrt(s.contact_length / (h.fraction * M_PI)); // the contact area of the whole sphere is pi a^2
  }
  if (!(h.a < HERTZ_MAX_A_OVER_R * h.R) && !h.check_load) {
    // The default case's own comparison on a load or material far from Hertz's range (-material_E 5): none.
    h.out_of_range = true;
    PetscFunctionReturn(0);
  }
  PetscCheck(h.a < HERTZ_MAX_A_OVER_R * h.R, comm, PETSC_ERR_USER_INPUT,
             "-report_hertz %.6g,%.6g: Johnson's contact %s for this load is %.6g, not small against R = %.6g; Hertz's theory "
             "holds for a << R (expected the radius R of the cylinder or sphere in contact)", h.R, h.P,
             dim == 2 ? "half-width" : "radius", h.a, h.R);
  PetscCall(FitProfile(state, nodes, s, h));
  PetscFunctionReturn(0);
}

namespace {
/// A material constant for the header: "%.6g", or "GROUP:%.6g, ..." when given per group.
std::string ValueText(double value, const std::vector<GroupValue> &groups) {
  char text[64];
  std::vector<std::string> items;
  for (const auto &g : groups) {
    std::snprintf(text, sizeof(text), "%.6g", g.value);
    items.push_back(g.group + ":" + text);
  }
  std::snprintf(text, sizeof(text), "%.6g", value);
  return groups.empty() ? std::string(text) : Join(items, ", ");
}
} // namespace

PetscErrorCode PrintHeader(MPI_Comm comm, const RunInfo &info, const Material &m, const SolvedState &state) {
  const Mesh &mesh = state.mesh;
  const DofMap &dofs = state.dofs;
  PetscInt owned = 0, candidates;
  PetscFunctionBeginUser;
  for (PetscInt v = 0; v < mesh.NumLocalVertices(); ++v) owned += mesh.Owned(v) && state.candidates[v];
  PetscCallMPI(MPI_Allreduce(&owned, &candidates, 1, MPIU_INT, MPI_SUM, comm));
  const std::string E = ValueText(m.E, m.E_groups), nu = ValueText(m.nu, m.nu_groups);
  if (mesh.Dim() == 2)
    PetscCall(PetscPrintf(comm, "signorini: 2D %s, plane %s, E = %s, nu = %s, thickness = %s\n", m.ModelText().c_str(),
                          m.plane_stress ? "stress" : "strain", E.c_str(), nu.c_str(),
                          ValueText(m.thickness, m.thickness_groups).c_str()));
  else
    PetscCall(PetscPrintf(comm, "signorini: 3D %s, E = %s, nu = %s\n", m.ModelText().c_str(), E.c_str(), nu.c_str()));
  if (mesh.NumBodies() > 1)
    PetscCall(PetscPrintf(comm, "  bodies: %" PetscInt_FMT " (connected groups of cells)\n", mesh.NumBodies()));
  PetscCall(PetscPrintf(comm, "  mesh %s: %" PetscInt_FMT " nodes, %" PetscInt_FMT " cells, %d rank(s)\n",
                        info.mesh_file.c_str(), mesh.NumGlobalNodes(), mesh.NumGlobalCells(), info.ranks));
  PetscCall(PetscPrintf(comm, "  unknowns: %" PetscInt_FMT " displacements, %" PetscInt_FMT " multipliers (%"
                        PetscInt_FMT " candidate nodes)\n", dofs.GlobalU(), dofs.GlobalLambda(), candidates));
  const SolverChoice &sc = state.stats.solver;
  PetscCall(PetscPrintf(comm, "  solver: %s (%s: %s)\n", SOLVER_PATH_NAMES[(int)sc.path], CHOSEN_BY_NAMES[(int)sc.by],
                        sc.why.c_str()));
  PetscFunctionReturn(0);
}

PetscErrorCode PrintSummary(MPI_Comm comm, const SolvedState &state, const ContactSummary &s, const HertzReport &h) {
  const SolveStats &st = state.stats;
  const int dim = state.mesh.Dim();
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(comm, "  %s after %" PetscInt_FMT " active-set iteration(s) in %" PetscInt_FMT
                        " load step(s): %" PetscInt_FMT " active pair(s) on %" PetscInt_FMT " node(s)\n",
                        ReasonName(st.reason), st.active_set_iterations, st.steps, s.active_pairs, s.active_nodes));
  const auto vec = [dim](const std::array<double, 3> &v) {
    char text[96];
    if (dim == 2) std::snprintf(text, sizeof(text), "(%.6g, %.6g)", v[0], v[1]);
    else std::snprintf(text, sizeof(text), "(%.6g, %.6g, %.6g)", v[0], v[1], v[2]);
    return std::string(text);
  };
  if (s.bodies)
    PetscCall(PetscPrintf(comm, "  contact force on the slave side %s, on the master side %s\n",
                          vec(s.contact_force).c_str(), vec(s.master_force).c_str()));
  PetscCall(PetscPrintf(comm, "  %s %s, applied load %s, reactions %s, balance %.2e\n",
                        s.bodies ? "total contact force" : "contact force",
                        vec(s.bodies ? std::array<double, 3>{s.contact_force[0] + s.master_force[0],
                                                             s.contact_force[1] + s.master_force[1],
                                                             s.contact_force[2] + s.master_force[2]}
                                     : s.contact_force).c_str(),
                        vec(s.applied_force).c_str(), vec(s.reaction_force).c_str(), s.force_balance));
  if (s.friction)
    PetscCall(PetscPrintf(comm, "  friction force %s (part of the contact force): %" PetscInt_FMT " stick, %" PetscInt_FMT
                          " slip node(s)\n", vec(s.friction_force).c_str(), state.certificate.friction.stick,
                          state.certificate.friction.slip));
  PetscCall(PetscPrintf(comm, "  contact %s %.6g, max pressure %.6g, max penetration %.3e, max |lambda g| "
                        "%.3e, max |u| %.6g\n", dim == 2 ? "length" : "area", s.contact_length, s.max_pressure,
                        s.max_penetration, s.complementarity, s.max_displacement));
  if (h.enabled && s.active_nodes == 0)
    PetscCall(PetscPrintf(comm, "  Hertz (R = %.6g, P = %.6g): no contact, nothing to compare\n", h.R, h.P));
  else if (h.enabled && h.contact_materials != 1)
    PetscCall(PetscPrintf(comm, "  Hertz (R = %.6g, P = %.6g): not compared, the cells along the contact boundary "
                          "have %d materials (Johnson's E* is that of one)\n", h.R, h.P, h.contact_materials));
  else if (h.enabled && h.out_of_range)
    PetscCall(PetscPrintf(comm, "  Hertz (R = %.6g, the default case's): not compared, Johnson's contact %s %.6g is not "
                          "small against R\n", h.R, dim == 2 ? "half-width" : "radius", h.a));
  else if (h.enabled) {
    // The label names the load compared (P_model), not -report_hertz's P: they differ when the default case's load
    // was changed (-bc_traction), whose report compares with the load the model carries.
    PetscCall(PetscPrintf(comm, "  Hertz (R = %.6g, P = %.6g): %s a = %.6g computed %.6g (%+.2f%%), peak pressure p0 = "
                          "%.6g computed %.6g (%+.2f%%, fit of %" PetscInt_FMT " nodal pressures)\n", h.R, h.P_model,
                          dim == 2 ? "half-width" : "contact radius", h.a, h.a_h, 100 * (h.a_h - h.a) / h.a, h.p0,
                          h.p0_h, 100 * (h.p0_h - h.p0) / h.p0, h.fit_nodes));
    PetscCall(PetscPrintf(comm, "    Johnson's values for the load the model stands for, %.6g (it is %.6g of the body "
                          "and carries %.6g)\n", h.P_model, h.fraction, h.fraction * h.P_model));
    if (h.a_fit > 0)
      PetscCall(PetscPrintf(comm, "    the fitted profile p^2 = p0^2 (1 - r^2/a^2) gives a = %.6g (%+.2f%%); the %s of the "
                            "active nodes moves by whole elements\n", h.a_fit, 100 * (h.a_fit - h.a) / h.a,
                            dim == 2 ? "contact length" : "contact area"));
  }
  PetscFunctionReturn(0);
}

namespace {

/// The certificate of the final state (summary.json "certificate").
void CertificateJson(JsonWriter &j, const Certificate &cert) {
  j.BeginObject("certificate")
      .Bool("satisfied", cert.Satisfied())
      .Number("max_penetration", cert.max_penetration)
      .Number("unpaired_penetration", cert.unpaired_penetration)
      .Number("gap_tol", cert.gap_tol)
      .Number("min_active_lambda", cert.min_active_lambda)
      .Number("max_inactive_lambda", cert.max_inactive_lambda)
      .Number("lambda_tol", cert.lambda_tol)
      .Number("complementarity", cert.complementarity)
      .Number("complementarity_tol", cert.complementarity_tol)
      .Number("equilibrium", cert.equilibrium)
      .Number("equilibrium_tol", cert.equilibrium_tol)
      .Integer("changes", cert.changes);
  if (cert.bodies) j.Number("pair_force_balance", cert.pair_force_balance).Number("pair_force_tol", cert.pair_force_tol);
  const FrictionCertificate &f = cert.friction;
  if (f.on)
    j.Number("friction_cone", f.cone)
        .Number("stick_slip", f.stick_slip)
        .Number("slip_rule", f.slip_rule)
        .Number("open_tangential_force", f.open_force)
        .Number("friction_force_tol", f.force_tol)
        .Number("slip_tol", f.slip_tol);
  j.EndObject();
}

/// The solver path and why it was chosen (summary.json "solver").
void SolverJson(JsonWriter &j, const SolverChoice &sc) {
  j.BeginObject("solver")
      .String("path", SOLVER_PATH_NAMES[(int)sc.path])
      .String("chosen_by", CHOSEN_BY_NAMES[(int)sc.by])
      .String("why", sc.why);
  if (sc.by == ChosenBy::AUTO)
    j.Number("budget_bytes", sc.budget_bytes)
        .Number("direct_bytes", sc.direct_bytes)
        .Number("direct_seconds", sc.direct_seconds)
        .Number("iterative_seconds", sc.iterative_seconds)
        .Number("factor_entries", sc.factor.entries)
        .Number("factor_flops", sc.factor.flops)
        .String("factor_estimate", sc.factor.analysed ? "analysis" : sc.factor.exact ? "node graph" : "model")
        .Bool("left_direct", sc.left_direct);
  j.EndObject();
}

/// The loop's counts and its iteration history (summary.json "iterations").
void IterationsJson(JsonWriter &j, const SolveStats &st) {
  j.BeginObject("iterations")
      .Integer("active_set", st.active_set_iterations)
      .Integer("solves", st.solves)
      .Integer("krylov", st.krylov_iterations)
      .Integer("load_steps", st.steps)
      .Integer("step_cuts", st.cuts)
      .Integer("stabilised_solves", st.stabilised_solves)
      .Integer("repairings", st.repairings)
      .Integer("search_widenings", st.search_widenings)
      .Integer("pivoted_sets", st.pivoted_sets)
      .Integer("krylov_fallbacks", st.krylov_fallbacks)
      .Number("search_radius", st.search_radius);
  j.BeginArray("history");
  for (const auto &r : st.history)
    j.BeginObject()
        .Integer("step", r.step)
        .Number("load_factor", r.load_factor)
        .Integer("iteration", r.iteration)
        .Integer("active", r.active)
        .Integer("changed", r.changed)
        .Number("min_lambda", r.min_lambda)
        .Number("max_penetration", r.max_penetration)
        .Number("residual", r.residual)
        .Integer("krylov", r.krylov)
        .Number("solve_time", r.solve_time)
        .EndObject();
  j.EndArray().EndObject();
}

/// The contact results (summary.json "contact"), vectors of dim components.
void ContactJson(JsonWriter &j, const ContactSummary &s, int dim) {
  const auto vec3 = [dim](const std::array<double, 3> &v) { return std::vector<double>(v.begin(), v.begin() + dim); };
  j.BeginObject("contact")
      .Integer("pairs", s.pairs)
      .Integer("active_pairs", s.active_pairs)
      .Integer("active_nodes", s.active_nodes)
      .Numbers("contact_force", vec3(s.contact_force));
  if (s.bodies) j.Numbers("master_contact_force", vec3(s.master_force));
  if (s.friction) j.Numbers("friction_force", vec3(s.friction_force));
  j.Numbers("applied_force", vec3(s.applied_force))
      .Numbers("reaction_force", vec3(s.reaction_force))
      .Number("force_balance", s.force_balance)
      .Number(dim == 2 ? "contact_length" : "contact_area", s.contact_length)
      .Number("max_pressure", s.max_pressure)
      .Number("max_penetration", s.max_penetration)
      .Number("complementarity", s.complementarity)
      .Number("min_lambda", s.min_lambda)
      .EndObject();
}

/// Johnson's values against the computed ones (summary.json "hertz"), when the report applies.
void HertzJson(JsonWriter &j, const HertzReport &h) {
  if (h.enabled && !h.out_of_range && h.contact_materials == 1)
    j.BeginObject("hertz")
        .Number("R", h.R)
        .Number("P", h.P)
        .Number("fraction", h.fraction)
        .Number("P_model", h.P_model)
        .Number("a", h.a)
        .Number("a_computed", h.a_h)
        .Number("p0", h.p0)
        .Number("p0_computed", h.p0_h)
        .Integer("fit_nodes", h.fit_nodes)
        .Number("a_fit", h.a_fit)
        .EndObject();
}

} // namespace

std::string SummaryJson(const RunInfo &info, const Material &m, const SolvedState &state, const ContactSummary &s,
                        const HertzReport &h) {
  const SolveStats &st = state.stats;
  const DofMap &dofs = state.dofs;
  const int dim = state.mesh.Dim();
  JsonWriter j;
  j.BeginObject();
  const Certificate &cert = state.certificate;
  j.String("version", SIGNORINI_VERSION);
  j.String("status", cert.Satisfied() ? "converged" : "not_converged").String("reason", ReasonName(st.reason));
  CertificateJson(j, cert);
  j.BeginObject("mesh")
      .String("file", info.mesh_file)
      .Integer("dim", dim)
      .Integer("nodes", state.mesh.NumGlobalNodes())
      .Integer("cells", state.mesh.NumGlobalCells())
      .Integer("ranks", info.ranks);
  if (state.mesh.NumBodies() > 1) j.Integer("bodies", state.mesh.NumBodies()); // a one-body summary as it always was
  j.EndObject();
  j.BeginObject("material");
  // A model given per group is an object of group: model, as -material_model GROUP:MODEL,... gives it.
  if (m.model_groups.empty()) j.String("model", m.ModelName());
  else {
    j.BeginObject("model");
    for (const auto &g : m.model_groups) j.String(g.group, Material::ModelNameOf(g.value != 0));
    j.EndObject();
  }
  j.String("plane", dim == 3 ? "none (3D)" : m.plane_stress ? "stress" : "strain");
  // A constant given per group is an object of group: value, as -material_E GROUP:VALUE,... gives it.
  const auto constant = [&j](const char *key, double value, const std::vector<GroupValue> &groups) {
    if (groups.empty()) {
      j.Number(key, value);
      return;
    }
    j.BeginObject(key);
    for (const auto &g : groups) j.Number(g.group, g.value);
    j.EndObject();
  };
  constant("E", m.E, m.E_groups);
  constant("nu", m.nu, m.nu_groups);
  constant("thickness", m.thickness, m.thickness_groups);
  j.EndObject();
  j.BeginObject("problem")
      .Integer("displacement_dofs", dofs.GlobalU())
      .Integer("multipliers", dofs.GlobalLambda())
      .Integer("candidate_nodes", s.candidates)
      .EndObject();
  SolverJson(j, st.solver);
  IterationsJson(j, st);
  j.BeginObject("timings");
  for (const auto &[k, v] : info.timings)
    j.Number(k, v);
  j.EndObject();
  ContactJson(j, s, dim);
  if (state.friction)
    j.BeginObject("friction")
        .Number("mu", state.friction->Coefficient())
        .Integer("stick_nodes", cert.friction.stick)
        .Integer("slip_nodes", cert.friction.slip)
        .EndObject();
  j.BeginObject("solution").Number("max_displacement", s.max_displacement).Number("strain_energy", s.strain_energy);
  j.EndObject();
  HertzJson(j, h);
  j.EndObject();
  return j.Text();
}

} // namespace signorini
