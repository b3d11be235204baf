// Reading and validating the material options.
#include "signorini/fem/material.hpp"
#include "signorini/core/handle.hpp"

#include "signorini/options/readers.hpp"
#include "signorini/core/parse.hpp"

#include <limits>
#include <string>

namespace signorini {

PetscErrorCode ReadMaterialOptions(MPI_Comm comm, Material &m) {
  const char *models[] = {"linear", "svk"};
  const char *planes[] = {"strain", "stress"};
  PetscInt model = m.model == MaterialModel::SVK ? 1 : 0, plane = m.plane_stress ? 1 : 0;
  PetscBool plane_given = PETSC_FALSE, thickness_given = PETSC_FALSE;
  const RealRange positive{0, std::numeric_limits<double>::infinity(), true, true};
  const std::string scale = "; E x thickness in [" + FormatNumber(STIFFNESS_SCALE_MIN) + ", " +
                            FormatNumber(STIFFNESS_SCALE_MAX) + "]";
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Material options", "signorini");
  const OptionsBlockGuard options_block(PetscOptionsObject); // ends the block on an error
  PetscCall(OptionsChoice(PetscOptionsObject, "-material_model",
                          "linear (small strain) or svk (St. Venant-Kirchhoff, Green-Lagrange)", "linear or svk",
                          models, 2, model));
  PetscCall(OptionsReal(PetscOptionsObject, "-material_E", ("Young's modulus" + scale).c_str(), positive, m.E));
  PetscCall(OptionsReal(PetscOptionsObject, "-material_nu", "Poisson's ratio", {-1, 0.5, true, true}, m.nu));
  PetscCall(OptionsChoice(PetscOptionsObject, "-material_plane", "2D assumption: strain or stress (2D meshes only)",
                          "strain or stress", planes, 2, plane, &plane_given));
  PetscCall(OptionsReal(PetscOptionsObject, "-material_thickness",
                        ("Out-of-plane thickness (2D meshes only)" + scale).c_str(), positive, m.thickness));
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-material_thickness", &thickness_given));
  PetscOptionsEnd();
  m.model = model == 1 ? MaterialModel::SVK : MaterialModel::LINEAR;
  m.plane_stress = plane == 1;
  m.plane_given = plane_given;
  m.thickness_given = thickness_given;
  // Nearly incompressible in plane strain or 3D: the displacement elements lock. The solve is exact for the discrete
  // problem (its residual at round-off), but that problem is too stiff: the default Hertz case's contact half-width is
  // 0.08 % off at nu = 0.49, 5.7 % at 0.499, 23 % at 0.4999 and 78 % at 0.499999. Plane stress does not lock
  // (lambda* = 2 lambda mu / (lambda + 2 mu) stays bounded).
  if (!m.plane_stress && m.nu > NEARLY_INCOMPRESSIBLE_NU)
    PetscCall(PetscPrintf(comm, "Note: -material_nu %s is nearly incompressible: the displacement elements lock "
                          "(lambda / mu = %s), so the results are too stiff (the default Hertz case's contact width is "
                          "5.7 %% too small at 0.499, 78 %% at 0.499999); plane stress does not lock\n",
                          FormatNumber(m.nu).c_str(), FormatNumber(2 * m.nu / (1 - 2 * m.nu)).c_str()));
  // E t is the scale of the stiffness and 1 / (E t) that of the multipliers' diagonal: outside these bounds the
  // discrete system is numerically singular (the Hertz case fails at E t = 2e-8) or overflows.
  const double k = m.E * m.thickness;
  PetscCheck(k >= STIFFNESS_SCALE_MIN && k <= STIFFNESS_SCALE_MAX, comm, PETSC_ERR_USER_INPUT,
             "-material_E %s with -material_thickness %s gives a stiffness scale E x thickness of %s; expected it in "
             "[%s, %s], outside which the discrete system is numerically singular or overflows (rescale the units)",
             FormatNumber(m.E).c_str(), FormatNumber(m.thickness).c_str(), FormatNumber(k).c_str(),
             FormatNumber(STIFFNESS_SCALE_MIN).c_str(), FormatNumber(STIFFNESS_SCALE_MAX).c_str());
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
