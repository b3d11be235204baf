// One run: options, mesh, set-up, contact solve, results, output; and the built-in default case.
#include "signorini/app/run.hpp"

#include "signorini/app/report.hpp"
#include "signorini/contact/contact_results.hpp"
#include "signorini/io/output.hpp"
#include "signorini/solver/contact_solver.hpp"

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace signorini {

namespace {

/// The built-in default case (2D Hertz: half cylinder R = 8 on a rigid flat, P = 10 per unit thickness). Its
/// options fill in whatever the user did not set when -mesh_file is absent.
PetscErrorCode ApplyDefaultCase() {
  PetscBool has_mesh;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-mesh_file", &has_mesh));
  if (has_mesh) PetscFunctionReturn(0);
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
  }
  PetscFunctionReturn(0);
}

/// Lists the saddle-point KSP's options for -help (the solve itself is not reached).
PetscErrorCode HelpKsp(MPI_Comm comm) {
  KSPH ksp;
  PetscFunctionBeginUser;
  PetscCall(KSPCreate(comm, ksp.out()));
  PetscCall(SetDefaultSolver(ksp));
  PetscCall(KSPSetFromOptions(ksp));
  SaddlePointOptions opts;
  PetscCall(ReadSaddlePointOptions(comm, opts));
  PetscFunctionReturn(0);
}

/// Length scale of the body (diagonal of its bounding box). Collective.
PetscErrorCode BodyDiagonal(const Mesh &mesh, double &L) {
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300}, glo[3], ghi[3];
  PetscFunctionBeginUser;
  for (PetscInt v = 0; v < mesh.NumLocalVertices(); ++v)
    for (int d = 0; d < mesh.Dim(); ++d) lo[d] = std::min(lo[d], mesh.X(v)[d]), hi[d] = std::max(hi[d], mesh.X(v)[d]);
  PetscCallMPI(MPI_Allreduce(lo, glo, 3, MPI_DOUBLE, MPI_MIN, mesh.Comm()));
  PetscCallMPI(MPI_Allreduce(hi, ghi, 3, MPI_DOUBLE, MPI_MAX, mesh.Comm()));
  L = 0;
  for (int d = 0; d < mesh.Dim(); ++d) L += (ghi[d] - glo[d]) * (ghi[d] - glo[d]);
  L = std::sqrt(L);
  PetscFunctionReturn(0);
}

/// Vertex and cell fields of the current state, for the HDF5 file (vectors padded to 3 components for ParaView).
PetscErrorCode CollectFields(ContactSolver &solver, const NodeContact &nodes, std::vector<Field> &fields,
                             std::vector<Field> &table) {
  const Mesh &mesh = solver.GetMesh();
  const int dim = mesh.Dim();
  const PetscInt nv = mesh.NumLocalVertices();
  PetscFunctionBeginUser;
  Field disp{"displacement", 3, false, std::vector<double>(3 * nv, 0.0)};
  Field disp2{"u", dim, false, solver.ULocal()};
  for (PetscInt v = 0; v < nv; ++v)
    for (int k = 0; k < dim; ++k) disp.values[3 * v + k] = solver.ULocal()[v * dim + k];
  std::vector<CellStress> cells;
  PetscCall(solver.GetAssembler().CellResults(solver.ULocal().data(), cells));
  Field strain{"strain", 6, true, {}}, stress{"stress", 6, true, {}}, vm{"von_mises", 1, true, {}};
  for (const auto &c : cells) {
    // XDMF Tensor6 order: xx, xy, xz, yy, yz, zz; the kernels' Voigt order is (xx, yy, xy) in 2D and
    // (xx, yy, zz, yz, xz, xy) in 3D.
    const auto &e = c.strain, &s = c.stress;
    if (dim == 2) {
      strain.values.insert(strain.values.end(), {e[0], e[2], 0, e[1], 0, 0});
      stress.values.insert(stress.values.end(), {s[0], s[2], 0, s[1], 0, c.stress_zz});
    } else {
      strain.values.insert(strain.values.end(), {e[0], e[5], e[4], e[1], e[3], e[2]});
      stress.values.insert(stress.values.end(), {s[0], s[5], s[4], s[1], s[3], s[2]});
    }
    vm.values.push_back(c.von_mises);
  }
  Field lambda{"contact_lambda", 1, false, nodes.lambda}, pressure{"contact_pressure", 1, false, nodes.pressure},
      gap{"contact_gap", 1, false, nodes.gap}, active{"contact_active", 1, false, nodes.active};
  fields = {disp, lambda, pressure, gap, active, strain, stress, vm};
  table = {disp2, {"lambda", 1, false, nodes.lambda}, {"pressure", 1, false, nodes.pressure},
           {"gap", 1, false, nodes.gap}, {"active", 1, false, nodes.active}};
  PetscFunctionReturn(0);
}

/// Reports options that were set but never read (a misspelled option must not pass silently).
PetscErrorCode ReportUnusedOptions(MPI_Comm comm) {
  PetscBool report = PETSC_TRUE;
  PetscInt n;
  char **names, **values;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetBool(nullptr, nullptr, "-options_left", &report, nullptr));
  PetscCall(PetscOptionsLeftGet(nullptr, &n, &names, &values));
  if (report)
    for (PetscInt i = 0; i < n; ++i)
      PetscCall(PetscPrintf(comm, "WARNING! option -%s%s%s was set but not used (misspelled?)\n", names[i],
                            values[i] ? " " : "", values[i] ? values[i] : ""));
  PetscCall(PetscOptionsLeftRestore(nullptr, &n, &names, &values));
  // PETSc's own report at PetscFinalize would repeat the list.
  PetscCall(PetscOptionsSetValue(nullptr, "-options_left", "0"));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode Run() {
  MPI_Comm comm = PETSC_COMM_WORLD;
  PetscLogStage stage_mesh, stage_setup, stage_solve, stage_output;
  PetscMPIInt size;
  RunInfo info;
  const double t_start = MPI_Wtime();
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  info.ranks = size;
  PetscCall(PetscLogStageRegister("Mesh", &stage_mesh));
  PetscCall(PetscLogStageRegister("Setup", &stage_setup));
  PetscCall(PetscLogStageRegister("ContactSolve", &stage_solve));
  PetscCall(PetscLogStageRegister("Output", &stage_output));
  PetscCall(ApplyDefaultCase());

  MeshOptions mesh_opts;
  Material material;
  BoundaryConditions bc;
  Obstacle obstacle;
  ContactOptions contact;
  SolverOptions solver_opts;
  OutputOptions output_opts;
  HertzReport hertz;
  PetscCall(ReadMeshOptions(comm, "", mesh_opts));
  PetscCall(ReadMaterialOptions(comm, material));
  PetscCall(ReadObstacle(comm, obstacle));
  PetscCall(ReadSolverOptions(comm, solver_opts));
  PetscCall(ReadOutputOptions(comm, output_opts));
  PetscCall(ReadReportOptions(comm, hertz));
  PetscBool help;
  PetscCall(PetscOptionsHasHelp(nullptr, &help));
  if (help) {
    PetscCall(ReadBoundaryConditions(comm, 0, bc));
    PetscCall(ReadContactOptions(comm, 1.0, material.E * material.thickness, contact));
    PetscCall(HelpKsp(comm));
    PetscCall(PetscOptionsSetValue(nullptr, "-options_left", "0"));
    PetscFunctionReturn(0);
  }
  info.mesh_file = mesh_opts.file;

  Mesh mesh;
  double t = MPI_Wtime();
  PetscCall(PetscLogStagePush(stage_mesh));
  PetscCall(mesh.Create(comm, mesh_opts));
  PetscCall(PetscLogStagePop());
  info.timings["mesh"] = MPI_Wtime() - t;
  // What the mesh's dimension decides: the components of loads and supports, the shapes, the 2D-only options.
  PetscCall(CheckMaterialDimension(comm, material, mesh.Dim()));
  PetscCall(ReadBoundaryConditions(comm, mesh.Dim(), bc));
  PetscCall(CheckObstacleDimension(comm, obstacle, mesh.Dim()));

  double L = 1;
  PetscCall(BodyDiagonal(mesh, L));
  PetscCall(CheckLoadScale(comm, bc, L, material.E, material.thickness));
  PetscCall(ReadContactOptions(comm, L, material.E * material.thickness, contact));
  OutputWriter output;
  PetscCall(output.Open(mesh, output_opts));

  t = MPI_Wtime();
  ContactSolver solver(mesh, material, bc, obstacle, contact, solver_opts);
  PetscCall(PetscLogStagePush(stage_setup));
  PetscCall(solver.Setup());
  PetscCall(PetscLogStagePop());
  info.timings["setup"] = MPI_Wtime() - t;

  double t_output = 0;
  NodeContact nodes;
  ContactSummary summary;
  std::vector<Field> fields, table;
  auto step_done = [&](PetscInt step, double factor) -> PetscErrorCode {
    PetscFunctionBeginUser;
    if (!output.Enabled()) PetscFunctionReturn(0);
    const double t0 = MPI_Wtime();
    PetscCall(PetscLogStagePush(stage_output));
    PetscCall(ComputeContactResults(solver, material, nodes, summary));
    PetscCall(CollectFields(solver, nodes, fields, table));
    PetscCall(output.WriteStep(step, factor, fields));
    PetscCall(PetscLogStagePop());
    t_output += MPI_Wtime() - t0;
    PetscFunctionReturn(0);
  };
  t = MPI_Wtime();
  PetscCall(PetscLogStagePush(stage_solve));
  PetscCall(solver.Solve(step_done));
  PetscCall(PetscLogStagePop());
  info.timings["contact_solve"] = MPI_Wtime() - t - t_output;
  info.timings["assembly"] = solver.Stats().time_assembly;
  info.timings["active_set"] = solver.Stats().time_active_set;
  info.timings["linear_solve"] = solver.Stats().time_solve;

  t = MPI_Wtime();
  PetscCall(PetscLogStagePush(stage_output));
  PetscCall(ComputeContactResults(solver, material, nodes, summary));
  ComputeHertz(material, summary, mesh.Dim(), hertz);
  PetscCall(PrintSummary(comm, info, material, solver, summary, hertz));
  if (output.Enabled()) {
    PetscCall(CollectFields(solver, nodes, fields, table));
    PetscCall(output.WriteNodeTable(table));
  }
  PetscCall(PetscLogStagePop());
  info.timings["output"] = t_output + MPI_Wtime() - t;
  info.timings["total"] = MPI_Wtime() - t_start;
  for (auto &[k, v] : info.timings) {
    double m;
    PetscCallMPI(MPI_Allreduce(&v, &m, 1, MPI_DOUBLE, MPI_MAX, comm));
    v = m;
  }
  PetscCall(output.Publish(SummaryJson(info, material, solver, summary, hertz)));
  PetscCall(ReportUnusedOptions(comm));
  PetscFunctionReturn(0);
}

} // namespace signorini
