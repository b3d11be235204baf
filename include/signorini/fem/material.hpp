// Material options and the elastic constants derived from them (prefix -material_).
#pragma once

#include <petscsys.h>

#include <array>
#include <string>
#include <vector>

namespace signorini {

class Mesh;

/// Bounds of the stiffness scale E x thickness (absolute): outside them the saddle-point system, with entries of order
/// E t and 1 / (E t), is numerically singular or overflows.
constexpr double STIFFNESS_SCALE_MIN = 1e-6, STIFFNESS_SCALE_MAX = 1e24;
/// Above this Poisson's ratio (plane strain, 3D) the run says that the displacement elements lock (ReadMaterial).
constexpr double NEARLY_INCOMPRESSIBLE_NU = 0.499;

enum class MaterialModel { LINEAR, SVK };

/// One item GROUP:VALUE of -material_E or -material_nu given per physical group of cells.
struct GroupValue {
  std::string group;
  double value = 0;
  std::string item; ///< as written, for messages
};

/// Isotropic elastic material in 2D (plane strain or plane stress) or 3D.
struct Material {
  MaterialModel model = MaterialModel::LINEAR; ///< -material_model linear | svk
  double E = 200.0;                            ///< -material_E, Young's modulus
  double nu = 0.3;                             ///< -material_nu, Poisson's ratio in (-1, 0.5)
  bool plane_stress = false;                   ///< -material_plane strain | stress
  double thickness = 1.0;                      ///< -material_thickness, out-of-plane thickness (scales stiffness and
                                               ///< distributed loads); per group: the largest
  bool plane_given = false, thickness_given = false; ///< the 2D-only options were set (an error on a 3D mesh)
  /// -material_E, -material_nu, -material_thickness given as GROUP:VALUE,... (each option on its own; empty: E, nu,
  /// thickness hold for every cell).
  std::vector<GroupValue> E_groups, nu_groups, thickness_groups;
  /// -material_model given as GROUP:MODEL,...: value 0 linear, 1 svk (empty: model holds for every cell; given, model
  /// is svk when some group is, and the run's loop is Newton's).
  std::vector<GroupValue> model_groups;
  /// Per group only (AssignCellMaterials): the distinct (E, nu, model: 0 linear, 1 svk, thickness) that cells of the
  /// run have, the same on every rank, and each local cell's index into them. Empty: one material, E, nu, model and
  /// thickness.
  std::vector<std::array<double, 4>> constants;
  std::vector<int> cell_constants;

  bool PerGroup() const {
    return !E_groups.empty() || !nu_groups.empty() || !model_groups.empty() || !thickness_groups.empty();
  }
  /// The largest Young's modulus of the run: E, or the largest of -material_E's groups.
  double MaxE() const;
  /// This material's model, plane and thickness with the constants E, nu (and no per-group data).
  Material With(double E, double nu) const;
  /// This material's plane with the constants k of AssignCellMaterials (E, nu, model, thickness).
  Material With(const std::array<double, 4> &k) const;
  /// The thickness of local cell c (2D; 1 in 3D, where it is not given).
  double CellThickness(PetscInt c) const {
    return cell_constants.empty() ? thickness : constants[cell_constants[(std::size_t)c]][3];
  }
  /// The model as given: "linear", "svk", or per group "soft:svk, stiff:linear".
  std::string ModelText() const;

  double Mu() const { return E / (2.0 * (1.0 + nu)); }
  double Lambda3D() const { return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)); }
  /// The first Lamé parameter of the in-plane law: 3D value in plane strain, 2 lambda mu / (lambda + 2 mu) in plane
  /// stress (sigma_zz = 0 eliminates eps_zz exactly, for linear and for St. Venant-Kirchhoff alike).
  double LambdaPlane() const {
    const double l = Lambda3D(), m = Mu();
    return plane_stress ? 2.0 * l * m / (l + 2.0 * m) : l;
  }
  const char *ModelName() const { return ModelNameOf(model == MaterialModel::SVK); }
  /// "svk" or "linear" (a model_groups value: nonzero is svk).
  static const char *ModelNameOf(bool svk) { return svk ? "svk" : "linear"; }
};

/// Reads and validates the -material_ options (E and thickness > 0 with E t in [STIFFNESS_SCALE_MIN,
/// STIFFNESS_SCALE_MAX], nu in (-1, 0.5)). Collective.
[[nodiscard]] PetscErrorCode ReadMaterialOptions(MPI_Comm comm, Material &m);

/// Resolves -material_E, -material_nu, -material_model and -material_thickness given per group on the mesh: each
/// group must be a physical group of cells of the mesh's dimension, and each option's groups must cover every cell
/// exactly once (an error names a cell, by its file number from 1, and its groups); each material's E x thickness
/// within the stiffness scale's bounds. Sets m.constants and m.cell_constants; nothing when no option is given per
/// group. Collective.
[[nodiscard]] PetscErrorCode AssignCellMaterials(const Mesh &mesh, Material &m);

/// Refuses -material_plane and -material_thickness on a 3D mesh (dim 3), where they mean nothing. Collective.
[[nodiscard]] PetscErrorCode CheckMaterialDimension(MPI_Comm comm, const Material &m, int dim);

} // namespace signorini
