// Reading and validating the material options.
#include "signorini/fem/material.hpp"
#include "signorini/core/handle.hpp"

#include "signorini/core/blocks.hpp"
#include "signorini/core/errors.hpp"
#include "signorini/mesh/mesh.hpp"

#include "signorini/options/readers.hpp"
#include "signorini/core/parse.hpp"

#include <algorithm>
#include <limits>
#include <string>

namespace signorini {

double Material::MaxE() const {
  double e = E_groups.empty() ? E : 0;
  for (const auto &g : E_groups) e = std::max(e, g.value);
  return e;
}

Material Material::With(double E_, double nu_) const {
  Material m;
  m.model = model;
  m.E = E_;
  m.nu = nu_;
  m.plane_stress = plane_stress;
  m.thickness = thickness;
  m.plane_given = plane_given;
  m.thickness_given = thickness_given;
  return m;
}

Material Material::With(const std::array<double, 4> &k) const {
  Material m = With(k[0], k[1]);
  m.model = k[2] != 0 ? MaterialModel::SVK : MaterialModel::LINEAR;
  m.thickness = k[3];
  return m;
}

std::string Material::ModelText() const {
  std::vector<std::string> items;
  for (const auto &g : model_groups) items.push_back(g.group + ":" + ModelNameOf(g.value != 0));
  return model_groups.empty() ? ModelName() : Join(items, ", ");
}

namespace {

/// Reads -material_model: one model for every cell (OptionsChoice), or a list GROUP:MODEL,... (told by a colon) into
/// by_group (value 0 linear, 1 svk); model is then svk when some group is.
PetscErrorCode OptionsModelOrGroups(PetscOptionItems *PetscOptionsObject, MaterialModel &model,
                                    std::vector<GroupValue> &by_group) {
  MPI_Comm comm = PetscOptionsObject->comm;
  const char *models[] = {"linear", "svk"};
  const char *name = "-material_model";
  const char *help = "linear (small strain) or svk (St. Venant-Kirchhoff, Green-Lagrange); or GROUP:MODEL,... per "
                     "physical group of cells covering every cell once (a run with an svk group solves by Newton's "
                     "method, its linear cells with their constant stiffness)";
  const char *raw_value = nullptr;
  PetscBool found = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsFindPair(nullptr, nullptr, name, &raw_value, &found));
  const std::string raw = found && raw_value ? raw_value : "";
  by_group.clear();
  if (raw.find(':') == std::string::npos) {
    PetscInt m = model == MaterialModel::SVK ? 1 : 0;
    PetscCall(OptionsChoice(PetscOptionsObject, name, help, "linear or svk", models, 2, m));
    model = m == 1 ? MaterialModel::SVK : MaterialModel::LINEAR;
    PetscFunctionReturn(0);
  }
  const char *expected = "GROUP:MODEL items such as ball:svk,plate:linear (MODEL linear or svk)";
  std::vector<std::string> items;
  PetscCall(OptionsStringList(PetscOptionsObject, name, help, "linear", expected, items));
  model = MaterialModel::LINEAR;
  for (const std::string &item : items) {
    const auto fields = Split(item, ':');
    const bool ok = fields.size() == 2 && !fields[0].empty() && (fields[1] == "linear" || fields[1] == "svk");
    PetscCheck(ok, comm, PETSC_ERR_USER_INPUT, "%s %s: item '%s' is malformed; expected %s", name, raw.c_str(),
               item.c_str(), expected);
    for (const auto &g : by_group)
      PetscCheck(g.group != fields[0], comm, PETSC_ERR_USER_INPUT,
                 "%s %s: group '%s' is given twice ('%s' and '%s'); expected each group once", name, raw.c_str(),
                 fields[0].c_str(), g.item.c_str(), item.c_str());
    const bool svk = fields[1] == "svk";
    by_group.push_back({fields[0], svk ? 1.0 : 0.0, item});
    if (svk) model = MaterialModel::SVK;
  }
  PetscFunctionReturn(0);
}

/// Reads -material_E or -material_nu (name): one value for every cell, read by OptionsReal exactly as a plain real
/// option, or a list GROUP:VALUE,... (told by a colon in the value) into by_group, each value checked against range.
/// symbol names the value in the expected form ("E", "NU").
PetscErrorCode OptionsRealOrGroups(PetscOptionItems *PetscOptionsObject, const char *name, const std::string &help,
                                   const char *symbol, const RealRange &range, double &value,
                                   std::vector<GroupValue> &by_group) {
  MPI_Comm comm = PetscOptionsObject->comm;
  const char *raw_value = nullptr;
  PetscBool found = PETSC_FALSE;
  PetscFunctionBeginUser;
  const std::string full_help = help + "; or GROUP:" + symbol + ",... per physical group of cells (surfaces in 2D, "
                               "volumes in 3D) covering every cell once";
  PetscCall(PetscOptionsFindPair(nullptr, nullptr, name, &raw_value, &found));
  const std::string raw = found && raw_value ? raw_value : "";
  by_group.clear();
  if (raw.find(':') == std::string::npos) {
    PetscCall(OptionsReal(PetscOptionsObject, name, full_help.c_str(), range, value));
    PetscFunctionReturn(0);
  }
  const std::string expected = std::string("GROUP:") + symbol + " items such as steel:" + FormatNumber(value) +
                               ",rubber:" + FormatNumber(value / 2) + " (" + symbol + " in " + range.Absolute() + ")";
  std::vector<std::string> items;
  PetscCall(OptionsStringList(PetscOptionsObject, name, full_help.c_str(), "no material", expected.c_str(), items));
  for (const std::string &item : items) {
    const auto fields = Split(item, ':');
    const auto v = fields.size() == 2 ? ParseFinite(fields[1]) : std::nullopt;
    PetscCheck(fields.size() == 2 && !fields[0].empty() && v, comm, PETSC_ERR_USER_INPUT,
               "%s %s: item '%s' is malformed; expected %s", name, raw.c_str(), item.c_str(), expected.c_str());
    PetscCheck(range.Contains(*v), comm, PETSC_ERR_USER_INPUT, "%s %s: item '%s' is out of range; expected %s", name,
               raw.c_str(), item.c_str(), expected.c_str());
    for (const auto &g : by_group)
      PetscCheck(g.group != fields[0], comm, PETSC_ERR_USER_INPUT,
                 "%s %s: group '%s' is given twice ('%s' and '%s'); expected each group once", name, raw.c_str(),
                 fields[0].c_str(), g.item.c_str(), item.c_str());
    by_group.push_back({fields[0], *v, item});
  }
  PetscFunctionReturn(0);
}

/// The stiffness scale E t within [STIFFNESS_SCALE_MIN, STIFFNESS_SCALE_MAX]. E t is the scale of the stiffness and
/// 1 / (E t) that of the multipliers' diagonal: outside these bounds the discrete system is numerically singular (the
/// Hertz case fails at E t = 2e-8) or overflows. E_text: -material_E's value or item.
PetscErrorCode CheckStiffnessScale(MPI_Comm comm, const std::string &E_text, double E, const std::string &t_text,
                                   double t) {
  const double k = E * t;
  PetscFunctionBeginUser;
  PetscCheck(k >= STIFFNESS_SCALE_MIN && k <= STIFFNESS_SCALE_MAX, comm, PETSC_ERR_USER_INPUT,
             "-material_E %s with -material_thickness %s gives a stiffness scale E x thickness of %s; expected it in "
             "[%s, %s], outside which the discrete system is numerically singular or overflows (rescale the units)",
             E_text.c_str(), t_text.c_str(), FormatNumber(k).c_str(),
             FormatNumber(STIFFNESS_SCALE_MIN).c_str(), FormatNumber(STIFFNESS_SCALE_MAX).c_str());
  PetscFunctionReturn(0);
}

/// The note that a Poisson's ratio (nu_text: the value or item) above NEARLY_INCOMPRESSIBLE_NU locks.
PetscErrorCode NoteLocking(MPI_Comm comm, const Material &m, const std::string &nu_text, double nu) {
  PetscFunctionBeginUser;
  // Nearly incompressible in plane strain or 3D: the displacement elements lock. The solve is exact for the discrete
  // problem (its residual at round-off), but that problem is too stiff: the default Hertz case's contact half-width is
  // 0.08 % off at nu = 0.49, 5.7 % at 0.499, 23 % at 0.4999 and 78 % at 0.499999. Plane stress does not lock
  // (lambda* = 2 lambda mu / (lambda + 2 mu) stays bounded).
  if (!m.plane_stress && nu > NEARLY_INCOMPRESSIBLE_NU)
    PetscCall(PetscPrintf(comm, "Note: -material_nu %s is nearly incompressible: the displacement elements lock "
                          "(lambda / mu = %s), so the results are too stiff (the default Hertz case's contact width is "
                          "5.7 %% too small at 0.499, 78 %% at 0.499999); plane stress does not lock\n",
                          nu_text.c_str(), FormatNumber(2 * nu / (1 - 2 * nu)).c_str()));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode ReadMaterialOptions(MPI_Comm comm, Material &m) {
  const char *planes[] = {"strain", "stress"};
  PetscInt plane = m.plane_stress ? 1 : 0;
  PetscBool plane_given = PETSC_FALSE, thickness_given = PETSC_FALSE;
  const RealRange positive{0, std::numeric_limits<double>::infinity(), true, true};
  const std::string scale = "; E x thickness in [" + FormatNumber(STIFFNESS_SCALE_MIN) + ", " +
                            FormatNumber(STIFFNESS_SCALE_MAX) + "]";
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Material options", "signorini");
  const OptionsBlockGuard options_block(PetscOptionsObject); // ends the block on an error
  PetscCall(OptionsModelOrGroups(PetscOptionsObject, m.model, m.model_groups));
  PetscCall(OptionsRealOrGroups(PetscOptionsObject, "-material_E", "Young's modulus" + scale, "E", positive, m.E,
                                m.E_groups));
  PetscCall(OptionsRealOrGroups(PetscOptionsObject, "-material_nu", "Poisson's ratio", "NU", {-1, 0.5, true, true},
                                m.nu, m.nu_groups));
  PetscCall(OptionsChoice(PetscOptionsObject, "-material_plane", "2D assumption: strain or stress (2D meshes only)",
                          "strain or stress", planes, 2, plane, &plane_given));
  PetscCall(OptionsRealOrGroups(PetscOptionsObject, "-material_thickness", "Out-of-plane thickness (2D meshes only)" +
                                scale, "T", positive, m.thickness, m.thickness_groups));
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-material_thickness", &thickness_given));
  PetscOptionsEnd();
  m.plane_stress = plane == 1;
  m.plane_given = plane_given;
  m.thickness_given = thickness_given;
  if (m.nu_groups.empty()) PetscCall(NoteLocking(comm, m, FormatNumber(m.nu), m.nu));
  for (const auto &g : m.nu_groups) PetscCall(NoteLocking(comm, m, g.item, g.value));
  // E x thickness: each value of one option against the other's single value; with both per group, for the
  // materials that cells have (AssignCellMaterials).
  if (m.thickness_groups.empty()) {
    if (m.E_groups.empty())
      PetscCall(CheckStiffnessScale(comm, FormatNumber(m.E), m.E, FormatNumber(m.thickness), m.thickness));
    for (const auto &g : m.E_groups)
      PetscCall(CheckStiffnessScale(comm, g.item, g.value, FormatNumber(m.thickness), m.thickness));
  } else {
    m.thickness = 0; // the largest, for the scales of the run (the cells' own come from AssignCellMaterials)
    for (const auto &g : m.thickness_groups) {
      if (m.E_groups.empty()) PetscCall(CheckStiffnessScale(comm, FormatNumber(m.E), m.E, g.item, g.value));
      m.thickness = std::max(m.thickness, g.value);
    }
  }
  PetscFunctionReturn(0);
}

namespace {

/// The items of one per-group option (-material_E or -material_nu) resolved on the mesh.
struct GroupOption {
  const char *name;
  const std::vector<GroupValue> &items;
  std::string Text() const {
    std::vector<std::string> t;
    for (const auto &i : items) t.push_back(i.item);
    return std::string(name) + " " + Join(t, ",");
  }
};

/// The item of each group of the mesh (-1: none), each item's group checked: a physical group of the mesh's cells.
PetscErrorCode ItemOfGroup(const Mesh &mesh, const GroupOption &o, std::vector<int> &item_of_group) {
  const auto &names = mesh.GroupNames();
  const auto &dims = mesh.GroupDims();
  const char *kind = mesh.Dim() == 2 ? "surface" : "volume";
  std::vector<std::string> cell_groups;
  PetscFunctionBeginUser;
  for (std::size_t g = 0; g < names.size(); ++g)
    if (dims[g] == mesh.Dim()) cell_groups.push_back(names[g]);
  const std::string list = cell_groups.empty() ? "(the mesh has none)" : Join(cell_groups, ", ");
  item_of_group.assign(names.size(), -1);
  for (std::size_t i = 0; i < o.items.size(); ++i) {
    const GroupValue &item = o.items[i];
    const auto it = std::find(names.begin(), names.end(), item.group);
    PetscCheck(it != names.end(), mesh.Comm(), PETSC_ERR_USER_INPUT,
               "%s: item '%s': physical group '%s' is not in the mesh; expected GROUP:VALUE items naming the mesh's "
               "physical %ss: %s", o.Text().c_str(), item.item.c_str(), item.group.c_str(), kind, list.c_str());
    const int g = (int)(it - names.begin());
    PetscCheck(dims[g] == mesh.Dim(), mesh.Comm(), PETSC_ERR_USER_INPUT,
               "%s: item '%s': physical group '%s' has dimension %d; expected GROUP:VALUE items naming physical %ss "
               "(dimension %d, groups of cells): %s", o.Text().c_str(), item.item.c_str(), item.group.c_str(),
               dims[g], kind, mesh.Dim(), list.c_str());
    item_of_group[g] = (int)i;
  }
  PetscFunctionReturn(0);
}

/// The error of the cell of smallest file index that the groups of o do not cover exactly once ("" if there is none
/// or it is on another rank), named by its file number from 1, its gmsh element tag and its groups. Collective.
PetscErrorCode CoverageError(const Mesh &mesh, const GroupOption &o, const std::vector<int> &item_of_group,
                             std::string &error) {
  PetscInt bad = PETSC_MAX_INT, local_bad = -1;
  PetscFunctionBeginUser;
  for (PetscInt c = 0; c < mesh.NumLocalCells(); ++c) {
    int n, count = 0;
    const int *g = mesh.CellGroups(c, n);
    for (int k = 0; k < n; ++k) count += item_of_group[g[k]] >= 0;
    if (count != 1 && mesh.CellOriginal(c) < bad) bad = mesh.CellOriginal(c), local_bad = c;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPIU_INT, MPI_MIN, mesh.Comm()));
  error.clear();
  if (bad == PETSC_MAX_INT) PetscFunctionReturn(0);
  // The gmsh tag of the cell is held by the rank whose block of file indices has it.
  PetscInt start, size;
  long long tag = -1;
  PetscCall(BlockOf(mesh.Comm(), mesh.NumGlobalCells(), start, size));
  if (bad >= start && bad < start + size) tag = (long long)mesh.CellTagsBlock()[bad - start];
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &tag, 1, MPI_LONG_LONG, MPI_MAX, mesh.Comm()));
  if (local_bad < 0 || mesh.CellOriginal(local_bad) != bad) PetscFunctionReturn(0);
  int n;
  const int *g = mesh.CellGroups(local_bad, n);
  std::vector<std::string> in, listed;
  for (int k = 0; k < n; ++k) {
    in.push_back("'" + mesh.GroupNames()[g[k]] + "'");
    if (item_of_group[g[k]] >= 0) listed.push_back(in.back());
  }
  error = o.Text() + ": cell " + std::to_string(bad + 1) + " (gmsh element " + std::to_string(tag) + ", in " +
          (in.empty() ? std::string("no physical group") : "physical groups " + Join(in, ", ")) + ") is in " +
          (listed.empty() ? std::string("none") : std::to_string(listed.size()) + " (" + Join(listed, ", ") + ")") +
          " of the option's groups; expected the groups to cover every cell exactly once";
  PetscFunctionReturn(0);
}

/// The item of each local cell for the per-group option o (empty when o has no items), checked. Collective.
PetscErrorCode CellItems(const Mesh &mesh, const GroupOption &o, std::vector<int> &cell_item) {
  std::vector<int> item_of_group;
  std::string error;
  PetscFunctionBeginUser;
  cell_item.clear();
  if (o.items.empty()) PetscFunctionReturn(0);
  PetscCall(ItemOfGroup(mesh, o, item_of_group));
  PetscCall(CoverageError(mesh, o, item_of_group, error));
  PetscCall(CheckCollective(mesh.Comm(), error.empty(), error));
  cell_item.resize(mesh.NumLocalCells());
  for (PetscInt c = 0; c < mesh.NumLocalCells(); ++c) {
    int n;
    const int *g = mesh.CellGroups(c, n);
    for (int k = 0; k < n; ++k)
      if (item_of_group[g[k]] >= 0) cell_item[c] = item_of_group[g[k]];
  }
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode AssignCellMaterials(const Mesh &mesh, Material &m) {
  std::vector<int> cell_E, cell_nu, cell_model, cell_t;
  PetscFunctionBeginUser;
  m.constants.clear();
  m.cell_constants.clear();
  if (!m.PerGroup()) PetscFunctionReturn(0);
  PetscCall(CellItems(mesh, {"-material_E", m.E_groups}, cell_E));
  PetscCall(CellItems(mesh, {"-material_nu", m.nu_groups}, cell_nu));
  PetscCall(CellItems(mesh, {"-material_model", m.model_groups}, cell_model));
  PetscCall(CellItems(mesh, {"-material_thickness", m.thickness_groups}, cell_t));
  // Each cell's (E item, nu item, model item, thickness item) tuple; the tuples that occur on some rank, in order and
  // with equal constants merged, are the run's materials (a handful: each gets its elasticity matrix once).
  const int nE = std::max<int>(1, (int)m.E_groups.size()), nnu = std::max<int>(1, (int)m.nu_groups.size());
  const int nmodel = std::max<int>(1, (int)m.model_groups.size());
  const int nt = std::max<int>(1, (int)m.thickness_groups.size()), ntuples = nE * nnu * nmodel * nt;
  const auto tuple_of = [&](PetscInt c) {
    return (((cell_E.empty() ? 0 : cell_E[c]) * nnu + (cell_nu.empty() ? 0 : cell_nu[c])) * nmodel +
            (cell_model.empty() ? 0 : cell_model[c])) * nt + (cell_t.empty() ? 0 : cell_t[c]);
  };
  std::vector<int> present(ntuples, 0), index(ntuples, -1);
  for (PetscInt c = 0; c < mesh.NumLocalCells(); ++c) present[tuple_of(c)] = 1;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, present.data(), ntuples, MPI_INT, MPI_MAX, mesh.Comm()));
  for (int p = 0; p < ntuples; ++p) {
    if (!present[p]) continue;
    const int e = p / (nnu * nmodel * nt), n = (p / (nmodel * nt)) % nnu, o = (p / nt) % nmodel, t = p % nt;
    const std::array<double, 4> k = {m.E_groups.empty() ? m.E : m.E_groups[e].value,
                                     m.nu_groups.empty() ? m.nu : m.nu_groups[n].value,
                                     m.model_groups.empty() ? (m.model == MaterialModel::SVK ? 1.0 : 0.0)
                                                            : m.model_groups[o].value,
                                     m.thickness_groups.empty() ? m.thickness : m.thickness_groups[t].value};
    if (!m.E_groups.empty() && !m.thickness_groups.empty())
      PetscCall(CheckStiffnessScale(mesh.Comm(), m.E_groups[e].item, k[0], m.thickness_groups[t].item, k[3]));
    const auto it = std::find(m.constants.begin(), m.constants.end(), k);
    index[p] = (int)(it - m.constants.begin());
    if (it == m.constants.end()) m.constants.push_back(k);
  }
  m.cell_constants.resize(mesh.NumLocalCells());
  for (PetscInt c = 0; c < mesh.NumLocalCells(); ++c) m.cell_constants[c] = index[tuple_of(c)];
  PetscFunctionReturn(0);
}

PetscErrorCode CheckMaterialDimension(MPI_Comm comm, const Material &m, int dim) {
  PetscFunctionBeginUser;
  PetscCheck(dim == 2 || !m.plane_given, comm, PETSC_ERR_USER_INPUT,
             "-material_plane is given but the mesh is 3D; expected it only with a 2D mesh (plane strain or stress)");
  PetscCheck(dim == 2 || !m.thickness_given, comm, PETSC_ERR_USER_INPUT,
             "-material_thickness is given but the mesh is 3D; expected it only with a 2D mesh (out-of-plane "
             "thickness)");
  PetscFunctionReturn(0);
}

} // namespace signorini
