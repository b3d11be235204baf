// One run: options, mesh, set-up, contact solve, results, output; and the built-in default case.
#include "signorini/app/run.hpp"

#include "signorini/core/parse.hpp"
#include "signorini/core/progress.hpp"
#include "signorini/io/output.hpp"
#include "signorini/linalg/pc_nullspace.hpp"
#include "signorini/loop/contact_solver.hpp"
#include "signorini/obstacles/obstacle_mesh.hpp"
#include "signorini/options/help.hpp"
#include "signorini/options/unused_options.hpp"
#include "signorini/post/contact_results.hpp"
#include "signorini/post/report.hpp"

#include <dmumps_c.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace signorini {

namespace {

/// The physical groups that the default case's supports, load and candidates name (its mesh has them).
const std::vector<std::string> DEFAULT_CASE_GROUPS = {"top_centre", "contact_point", "top", "contact"};

/// The built-in default case (2D Hertz: half cylinder R = 8 on a rigid flat, P = 10 per unit thickness). Its options
/// fill in whatever the run does not set (docs/cases.md: any option given overrides the default case's value), unless
/// the run gives a case of its own: a -mesh_file together with any support, load, obstacle or candidate group. A
/// -mesh_file alone (a finer Hertz mesh, meshes/hertz.geo with -mesh_size_factor) keeps the rest of the default case
/// instead of running a body that nothing loads or holds; on_user_mesh then tells CheckDefaultCaseMesh to check it.
/// hertz_filled: the default case filled in -report_hertz (its P then need not be the load the run gives).
PetscErrorCode ApplyDefaultCase(bool &on_user_mesh, bool &hertz_filled) {
  PetscBool has_mesh;
  PetscFunctionBeginUser;
  on_user_mesh = false;
  hertz_filled = false;
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-mesh_file", &has_mesh));
  if (has_mesh) {
    std::vector<std::string> own = {"-bc_dirichlet", "-bc_traction", "-bc_pressure", "-bc_point_force",
                                    "-bc_body_force", "-obstacle_mesh", "-contact_groups", "-contact_pairs"};
    for (const ShapeType &shape : ShapeRegistry()) own.push_back(shape.option);
    for (const std::string &name : own) {
      PetscBool set;
      PetscCall(PetscOptionsHasName(nullptr, nullptr, name.c_str(), &set));
      if (set) PetscFunctionReturn(0);
    }
    on_user_mesh = true;
  }
  const std::string mesh = std::string(SIGNORINI_SOURCE_DIR) + "/meshes/hertz.msh";
  const std::vector<std::pair<const char *, std::string>> defaults = {
      {"-mesh_file", mesh},
      {"-material_E", "200"},
      {"-material_nu", "0.3"},
      {"-bc_dirichlet", "top_centre:x,contact_point:x"},
      {"-bc_traction", "top:0:-0.625"},
      {"-obstacle_segments", "-12,-8,12,-8"},
      {"-contact_groups", "contact"},
      {"-report_hertz", "8,10"}};
  for (const auto &[name, value] : defaults) {
    PetscBool set;
    PetscCall(PetscOptionsHasName(nullptr, nullptr, name, &set));
    if (!set) PetscCall(PetscOptionsSetValue(nullptr, name, value.c_str()));
    if (!set && std::string(name) == "-report_hertz") hertz_filled = true;
  }
  PetscFunctionReturn(0);
}

/// The default case on the user's -mesh_file: its supports, load and candidates need a 2D mesh with its groups.
/// Without this check the first missing group would be reported against an option the user never gave.
PetscErrorCode CheckDefaultCaseMesh(MPI_Comm comm, const std::string &file, const Mesh &mesh) {
  std::vector<std::string> missing;
  PetscFunctionBeginUser;
  for (const std::string &g : DEFAULT_CASE_GROUPS)
    if (std::find(mesh.GroupNames().begin(), mesh.GroupNames().end(), g) == mesh.GroupNames().end())
      missing.push_back(g);
  const std::string what = mesh.Dim() != 2 ? "is " + std::to_string(mesh.Dim()) + "D"
                                           : "has no physical group " + Join(missing, ", ");
  PetscCheck(mesh.Dim() == 2 && missing.empty(), comm, PETSC_ERR_USER_INPUT,
             "-mesh_file %s is given without supports, loads, obstacles, contact groups or pairs, so the run is the default "
             "case (2D Hertz) on it, which needs a 2D mesh with the physical groups %s; this mesh %s; expected a mesh "
             "of the Hertz geometry, or the case's own -bc_dirichlet, loads (-bc_traction, -bc_pressure, "
             "-bc_point_force, -bc_body_force), -obstacle_*, -contact_groups or -contact_pairs (an -options_file of a "
             "case)",
             file.c_str(), Join(DEFAULT_CASE_GROUPS, ", ").c_str(), what.c_str());
  PetscFunctionReturn(0);
}

/// Lists the saddle-point KSP's options for -help, with the user's solver preset: the KSP is set up on a tiny
/// saddle-point matrix (per rank two u rows and one multiplier row, diag(1, 1, -1), split into the index sets u and
/// lambda as the real system is) so that the options of the factorisation and of the fieldsplit blocks are listed too.
PetscErrorCode HelpKsp(MPI_Comm comm) {
  KSPH ksp;
  MatH A;
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  // The program's own group about the saddle-point system comes before PETSc's groups of the solver.
  SaddlePointOptions opts;
  PetscCall(ReadSaddlePointOptions(comm, opts));
  // The stand-in matrix's own options (-mat_*, unprefixed) are PETSc's generic ones: they join the held text that is
  // listed last, so that the solver's groups follow the program's.
  {
    const GenericHelpHeld held; // while the stand-in is made; the printers come back however it ends
    PetscCall(MatCreateAIJ(comm, 3, 3, PETSC_DETERMINE, PETSC_DETERMINE, 1, nullptr, 0, nullptr, A.out()));
    for (PetscInt i = 0; i < 3; ++i)
      PetscCall(MatSetValue(A, 3 * rank + i, 3 * rank + i, i < 2 ? 1.0 : -1.0, INSERT_VALUES));
    PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  }
  ISH u, lambda;
  PetscCall(ISCreateStride(comm, 2, 3 * rank, 1, u.out()));
  PetscCall(ISCreateStride(comm, 1, 3 * rank + 2, 1, lambda.out()));
  PetscCall(PCNullSpaceRegister());
  PetscCall(KSPCreate(comm, ksp.out()));
  PetscCall(KSPSetOperators(ksp, A, A));
  PetscCall(SetDefaultSolver(ksp));
  PetscCall(KSPSetFromOptions(ksp));
  // PETSc lists no Krylov tolerance for KSPPREONLY, which reads none (the set-up refuses them then: say so).
  PetscBool preonly;
  PetscCall(PetscObjectTypeCompare((PetscObject)ksp.get(), KSPPREONLY, &preonly));
  if (preonly)
    PetscCall(PetscPrintf(comm, "  -contact_ksp_rtol, -contact_ksp_atol, -contact_ksp_divtol, -contact_ksp_max_it: "
                          "not listed: -contact_ksp_type preonly (this run's direct solve) reads none of them, and the "
                          "set-up refuses them; they apply with an iterative solver (-contact_ksp_type other than "
                          "preonly, or a fieldsplit preset)\n"));
  PC pc;
  PetscBool fieldsplit;
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCFIELDSPLIT, &fieldsplit));
  if (fieldsplit) {
    PetscCall(PCFieldSplitSetIS(pc, "u", u));
    PetscCall(PCFieldSplitSetIS(pc, "lambda", lambda));
  }
  // The null-space preconditioner needs the nested matrix of a run: its PCSetFromOptions listed its block's solver.
  PetscBool nullspace;
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCNULLSPACE, &nullspace));
  if (!nullspace) PetscCall(KSPSetUp(ksp));
  PetscFunctionReturn(0);
}

/// Vertex and cell fields of the current state, for the HDF5 file (vectors padded to 3 components for ParaView).
PetscErrorCode StepFields(ContactSolver &solver, const NodeContact &nodes, std::vector<Field> &fields) {
  const int dim = solver.GetMesh().Dim();
  PetscFunctionBeginUser;
  // The displacement and the cell fields are made when they are written (Field::fill), the cell fields each by a pass
  // over the cells.
  const auto displacement = [&solver, dim](std::vector<double> &values) -> PetscErrorCode {
    const PetscInt nv = solver.GetMesh().NumLocalVertices();
    values.assign(3 * nv, 0.0);
    for (PetscInt v = 0; v < nv; ++v)
      for (int k = 0; k < dim; ++k) values[3 * v + k] = solver.ULocal()[v * dim + k];
    return 0;
  };
  enum { STRAIN, STRESS, VON_MISES };
  const auto cell_field = [&solver, dim](int which) {
    return [&solver, dim, which](std::vector<double> &values) -> PetscErrorCode {
      const int ncomp = which == VON_MISES ? 1 : 6;
      PetscFunctionBeginUser;
      values.assign(ncomp * solver.GetMesh().NumLocalCells(), 0.0);
      PetscCall(solver.GetAssembler().CellResults(solver.ULocal().data(), [&](PetscInt c, const CellStress &r) {
        if (which == VON_MISES) {
          values[c] = r.von_mises;
          return;
        }
        // VTK's order of a symmetric tensor (xx, yy, zz, xy, yz, xz): ParaView names six components so (output.cpp).
        // The kernels' Voigt order is (xx, yy, xy) in 2D and (xx, yy, zz, yz, xz, xy) in 3D.
        const auto &e = r.strain, &s = r.stress;
        const std::array<double, 6> t =
            which == STRAIN ? (dim == 2 ? std::array<double, 6>{e[0], e[1], r.strain_zz, e[2], 0, 0}
                                        : std::array<double, 6>{e[0], e[1], e[2], e[5], e[3], e[4]})
                            : (dim == 2 ? std::array<double, 6>{s[0], s[1], r.stress_zz, s[2], 0, 0}
                                        : std::array<double, 6>{s[0], s[1], s[2], s[5], s[3], s[4]});
        std::copy(t.begin(), t.end(), values.begin() + 6 * c);
      }));
      PetscFunctionReturn(0);
    };
  };
  fields.push_back({"displacement", 3, false, {}, true, displacement});
  fields.push_back({"contact_lambda", 1, false, nodes.lambda, true});
  fields.push_back({"contact_pressure", 1, false, nodes.pressure, true});
  fields.push_back({"contact_gap", 1, false, nodes.gap, true});
  fields.push_back({"contact_active", 1, false, nodes.active, true});
  if (!nodes.friction.empty()) {
    // Friction: dim values per vertex, as 3-component vectors.
    const auto vector3 = [dim](const std::vector<double> &v) {
      std::vector<double> out(v.size() / dim * 3, 0.0);
      for (std::size_t i = 0; i < v.size() / dim; ++i)
        for (int k = 0; k < dim; ++k) out[3 * i + k] = v[i * dim + k];
      return out;
    };
    fields.push_back({"contact_friction", 3, false, vector3(nodes.friction), true});
    fields.push_back({"contact_friction_traction", 3, false, vector3(nodes.friction_traction), true});
    fields.push_back({"contact_slip", 3, false, vector3(nodes.slip), true});
    fields.push_back({"contact_friction_state", 1, false, nodes.friction_state, true});
  }
  fields.push_back({"strain", 6, true, {}, false, cell_field(STRAIN)});
  fields.push_back({"stress", 6, true, {}, false, cell_field(STRESS)});
  fields.push_back({"von_mises", 1, true, {}, false, cell_field(VON_MISES)});
  PetscFunctionReturn(0);
}

/// The columns of the node table of the current state: the displacement and the contact fields, and with several
/// bodies each node's body (a one-body table as it always was).
std::vector<Field> NodeTableFields(ContactSolver &solver, const NodeContact &nodes) {
  const Mesh &mesh = solver.GetMesh();
  std::vector<Field> fields = {{"u", mesh.Dim(), false, solver.ULocal()}, {"lambda", 1, false, nodes.lambda},
                               {"pressure", 1, false, nodes.pressure}, {"gap", 1, false, nodes.gap},
                               {"active", 1, false, nodes.active}};
  if (!nodes.friction.empty()) {
    fields.push_back({"friction", mesh.Dim(), false, nodes.friction});
    fields.push_back({"friction_traction", mesh.Dim(), false, nodes.friction_traction});
    fields.push_back({"slip", mesh.Dim(), false, nodes.slip});
    fields.push_back({"friction_state", 1, false, nodes.friction_state});
  }
  if (mesh.NumBodies() > 1) {
    std::vector<double> body(mesh.NumLocalVertices());
    for (PetscInt v = 0; v < mesh.NumLocalVertices(); ++v) body[v] = (double)mesh.VertexBody(v);
    fields.push_back({"body", 1, false, body});
  }
  return fields;
}

/// -version: the versions of the program and of the libraries that decide its results, and nothing else. Collective.
PetscErrorCode PrintVersion(MPI_Comm comm) {
  char petsc[256], mpi[MPI_MAX_LIBRARY_VERSION_STRING];
  int length;
  PetscFunctionBeginUser;
  PetscCall(PetscGetVersion(petsc, sizeof(petsc)));
  for (size_t n = std::strlen(petsc); n > 0 && petsc[n - 1] == ' '; --n) petsc[n - 1] = '\0';
  PetscCallMPI(MPI_Get_library_version(mpi, &length));
  std::string mpi_first(mpi, std::min<size_t>(length, std::strcspn(mpi, ",\n")));
  PetscCall(PetscPrintf(comm, "signorini %s\n%s\nMUMPS %s\n%s\n", SIGNORINI_VERSION, petsc, MUMPS_VERSION,
                        mpi_first.c_str()));
  PetscCall(PetscOptionsSetValue(nullptr, "-options_left", "0"));
  PetscFunctionReturn(0);
}

/// A case as its options describe it, before the mesh is read.
struct Case {
  bool default_on_user_mesh = false; ///< the default case on the user's -mesh_file (CheckDefaultCaseMesh)
  MeshOptions mesh_opts;
  Material material;
  BoundaryConditions bc;
  Obstacle obstacle;
  ContactOptions contact;
  SolverOptions solver_opts;
  OutputOptions output_opts;
  HertzReport hertz;
};

/// The default case where the run gives none, then each component's options that need no mesh. Collective.
PetscErrorCode ReadCase(MPI_Comm comm, bool help, Case &c) {
  PetscFunctionBeginUser;
  if (help)
    PetscCall(PetscPrintf(comm, "signorini: frictionless (Signorini) contact of elastic bodies against rigid "
                          "obstacles and between bodies.\nEvery input is a PETSc option. The built-in 2D Hertz case (options/hertz.yml) "
                          "fills in every option not given, unless the run gives a case of its own: -mesh_file with "
                          "any of -bc_*, -obstacle_*, -contact_groups, -contact_pairs. -version prints the program's, PETSc's, MUMPS's "
                          "and MPI's versions.\n\n"));
  bool hertz_filled;
  PetscCall(ApplyDefaultCase(c.default_on_user_mesh, hertz_filled));
  PetscCall(ReadProgressOptions(comm));
  PetscCall(ReadMeshOptions(comm, "", c.mesh_opts));
  PetscCall(ReadMaterialOptions(comm, c.material));
  PetscCall(ReadObstacle(comm, c.obstacle));
  PetscCall(ReadSolverOptions(comm, c.material.model, c.solver_opts));
  PetscCall(ReadOutputOptions(comm, c.output_opts));
  PetscCall(ReadReportOptions(comm, c.hertz));
  c.hertz.check_load = !hertz_filled;
  PetscFunctionReturn(0);
}

/// -help: the groups that need the mesh's dimension or scale (read with stand-in values), the saddle-point solver's,
/// then PETSc's generic options. Collective.
PetscErrorCode ListCaseHelp(MPI_Comm comm, Case &c) {
  PetscFunctionBeginUser;
  PetscCall(ReadBoundaryConditions(comm, 0, c.bc));
  PetscCall(ReadContactOptions(comm, 0, 1.0, c.material.MaxE() * c.material.thickness, c.contact));
  PetscCall(HelpKsp(comm));
  PetscCall(PrintGenericHelp(comm));
  PetscCall(PetscOptionsSetValue(nullptr, "-options_left", "0"));
  PetscFunctionReturn(0);
}

/// What the mesh decides of the case: the default case's groups, the dimension of the material, supports, loads and
/// shapes, the meshed obstacles, and the problem's scale (body: its bounding box, whose diagonal L is the length scale
/// of the load and contact checks). Collective.
PetscErrorCode CheckCaseOnMesh(MPI_Comm comm, const Mesh &mesh, Case &c, Box &body) {
  PetscFunctionBeginUser;
  if (c.default_on_user_mesh) PetscCall(CheckDefaultCaseMesh(comm, c.mesh_opts.file, mesh));
  PetscCall(CheckMaterialDimension(comm, c.material, mesh.Dim()));
  PetscCall(AssignCellMaterials(mesh, c.material));
  PetscCall(ReadBoundaryConditions(comm, mesh.Dim(), c.bc));
  PetscCall(CheckLoadGroups(mesh, c.bc));
  PetscCall(CheckObstacleDimension(comm, c.obstacle, mesh.Dim()));
  PetscCall(LoadObstacleMeshes(comm, mesh.Dim(), c.obstacle));
  PetscCall(mesh.BoundingBox(body.lo, body.hi));
  const double L = std::sqrt(std::pow(body.hi[0] - body.lo[0], 2) + std::pow(body.hi[1] - body.lo[1], 2) +
                             std::pow(body.hi[2] - body.lo[2], 2));
  // The stiffness scale of the load checks and of the complementarity constant: the largest E of the run (the only one
  // with one material), so that the stiffest part's multipliers are well scaled.
  const double E = c.material.MaxE();
  PetscCall(CheckLoadScale(comm, c.bc, L, E, c.material.thickness));
  PetscCall(ReadContactOptions(comm, mesh.Dim(), L, E * c.material.thickness, c.contact));
  PetscCall(CheckContactInputs(mesh, c.obstacle, c.contact));
  PetscFunctionReturn(0);
}

/// After the solve: the contact results, the summary, the node table, the timings (maximum over the ranks), the
/// check of unread options and the publication of the output (stage: the Output log stage; t_output: the seconds the
/// load steps' output took; t_start: when the run started). Collective.
PetscErrorCode Finish(MPI_Comm comm, ContactSolver &solver, Case &c, OutputWriter &output, PetscLogStage stage,
                      double t_output, double t_start, RunInfo &info) {
  NodeContact nodes;
  ContactSummary summary;
  PetscFunctionBeginUser;
  const double t = MPI_Wtime();
  PetscCall(PetscLogStagePush(stage));
  ProgressBegin("results and output");
  PetscCall(ComputeContactResults(solver.State(), c.material, nodes, summary));
  PetscCall(ComputeHertz(solver.State(), c.material, nodes, summary, c.hertz));
  PetscCall(PrintSummary(comm, solver.State(), summary, c.hertz));
  if (output.Enabled()) PetscCall(output.WriteNodeTable(NodeTableFields(solver, nodes)));
  PetscCall(PetscLogStagePop());
  info.timings["output"] = t_output + MPI_Wtime() - t;
  info.timings["total"] = MPI_Wtime() - t_start;
  for (auto &[k, v] : info.timings) {
    double m;
    PetscCallMPI(MPI_Allreduce(&v, &m, 1, MPI_DOUBLE, MPI_MAX, comm));
    v = m;
  }
  PetscCall(CheckUnusedOptions(comm, UnusedOptions::AFTER_SOLVE));
  PetscCall(output.Publish(SummaryJson(info, c.material, solver.State(), summary, c.hertz)));
  ProgressEnd();
  PetscFunctionReturn(0);
}

/// The log stages of a run, as -log_view shows them.
struct Stages {
  PetscLogStage mesh, setup, solve, output;
};

/// The solver's set-up (supports, pairs, numbering, pattern) in its log stage, timed. Collective.
PetscErrorCode SetupSolver(ContactSolver &solver, PetscLogStage stage, RunInfo &info) {
  PetscFunctionBeginUser;
  const double t = MPI_Wtime();
  PetscCall(PetscLogStagePush(stage));
  ProgressBegin("set-up (supports, contact pairs, numbering, matrix pattern)");
  PetscCall(solver.Setup());
  ProgressEnd();
  PetscCall(PetscLogStagePop());
  info.timings["setup"] = MPI_Wtime() - t;
  PetscFunctionReturn(0);
}

/// Opens the output directory once every input but the saddle-point solver's options has been checked, and prints
/// the run's header. Collective.
PetscErrorCode OpenOutput(MPI_Comm comm, Mesh &mesh, const Case &c, const Box &body, ContactSolver &solver,
                          const RunInfo &info, OutputWriter &output) {
  PetscFunctionBeginUser;
  // Every option but the saddle-point solver's has been read by now: a misspelt one stops the run here.
  PetscCall(CheckUnusedOptions(comm, UnusedOptions::AFTER_SETUP));
  // The output directory is opened once the set-up has checked the inputs it reads (groups, supports), so that
  // these errors leave no directory behind.
  PetscCall(output.Open(mesh, c.output_opts));
  mesh.ReleaseDM(); // the mesh's own arrays serve from here on
  output.SetObstacle(c.obstacle, body);
  PetscCall(output.SetContactBoundary(solver.Candidates()));
  PetscCall(PrintHeader(comm, info, c.material, solver.State()));
  PetscFunctionReturn(0);
}

/// The load steps, each converged one written (output's stage; t_output: the time that took), timed. Collective.
PetscErrorCode SolveSteps(ContactSolver &solver, const Case &c, OutputWriter &output, const Stages &stages,
                          double &t_output, RunInfo &info) {
  PetscFunctionBeginUser;
  t_output = 0;
  NodeContact nodes;
  ContactSummary summary;
  auto step_done = [&](PetscInt step, double factor) -> PetscErrorCode {
    PetscFunctionBeginUser;
    if (!output.Enabled()) PetscFunctionReturn(0);
    const double t0 = MPI_Wtime();
    PetscCall(PetscLogStagePush(stages.output));
    ProgressBegin("output of load step");
    PetscCall(ComputeContactResults(solver.State(), c.material, nodes, summary));
    std::vector<Field> fields; // made one at a time as they are written
    PetscCall(StepFields(solver, nodes, fields));
    PetscCall(output.WriteStep(step, factor, fields));
    ProgressEnd();
    PetscCall(PetscLogStagePop());
    t_output += MPI_Wtime() - t0;
    PetscFunctionReturn(0);
  };
  const double t = MPI_Wtime();
  PetscCall(PetscLogStagePush(stages.solve));
  ProgressBegin("contact solve");
  PetscCall(solver.Solve(step_done));
  ProgressEnd();
  PetscCall(PetscLogStagePop());
  info.timings["contact_solve"] = MPI_Wtime() - t - t_output;
  info.timings["assembly"] = solver.Stats().time_assembly;
  info.timings["active_set"] = solver.Stats().time_active_set;
  info.timings["linear_solve"] = solver.Stats().time_solve;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode Run() {
  MPI_Comm comm = PETSC_COMM_WORLD;
  Stages stages;
  PetscMPIInt size;
  RunInfo info;
  const double t_start = MPI_Wtime();
  PetscFunctionBeginUser;
  ListProgramHelp();
  PetscCallMPI(MPI_Comm_size(comm, &size));
  info.ranks = size;
  PetscCall(PetscLogStageRegister("Mesh", &stages.mesh));
  PetscCall(PetscLogStageRegister("Setup", &stages.setup));
  PetscCall(PetscLogStageRegister("ContactSolve", &stages.solve));
  PetscCall(PetscLogStageRegister("Output", &stages.output));
  PetscBool version;
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-version", &version));
  if (version) {
    PetscCall(PrintVersion(comm));
    PetscFunctionReturn(0);
  }
  PetscBool help;
  PetscCall(PetscOptionsHasHelp(nullptr, &help));
  Case c;
  PetscCall(ReadCase(comm, help, c));
  if (help) {
    PetscCall(ListCaseHelp(comm, c));
    PetscFunctionReturn(0);
  }
  Mesh mesh;
  Box body;
  const double t = MPI_Wtime();
  PetscCall(PetscLogStagePush(stages.mesh));
  PetscCall(mesh.Create(comm, c.mesh_opts));
  PetscCall(PetscLogStagePop());
  info.mesh_file = mesh.Path();
  info.timings["mesh"] = MPI_Wtime() - t;
  PetscCall(CheckCaseOnMesh(comm, mesh, c, body));
  ContactSolver solver(mesh, c.material, c.bc, c.obstacle, c.contact, c.solver_opts);
  PetscCall(SetupSolver(solver, stages.setup, info));
  OutputWriter output;
  PetscCall(OpenOutput(comm, mesh, c, body, solver, info, output));
  double t_output;
  PetscCall(SolveSteps(solver, c, output, stages, t_output, info));
  PetscCall(Finish(comm, solver, c, output, stages.output, t_output, t_start, info));
  PetscFunctionReturn(0);
}

} // namespace signorini
