// Reading and validating the material options.
#include "signorini/fem/material.hpp"

#include <cmath>
#include <cstring>

namespace signorini {

PetscErrorCode ReadMaterialOptions(MPI_Comm comm, Material &m) {
  const char *models[] = {"linear", "svk"};
  const char *planes[] = {"strain", "stress"};
  PetscInt model = m.model == MaterialModel::SVK ? 1 : 0, plane = m.plane_stress ? 1 : 0;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Material options", "signorini");
  PetscCall(PetscOptionsEList("-material_model", "linear (small strain) or svk (St. Venant-Kirchhoff, Green-Lagrange)",
                              "", models, 2, models[model], &model, nullptr));
  PetscCall(PetscOptionsReal("-material_E", "Young's modulus", "", m.E, &m.E, nullptr));
  PetscCall(PetscOptionsReal("-material_nu", "Poisson's ratio", "", m.nu, &m.nu, nullptr));
  PetscCall(PetscOptionsEList("-material_plane", "2D assumption: strain or stress", "", planes, 2, planes[plane],
                              &plane, nullptr));
  PetscCall(PetscOptionsReal("-material_thickness", "Out-of-plane thickness", "", m.thickness, &m.thickness, nullptr));
  PetscOptionsEnd();
  m.model = model == 1 ? MaterialModel::SVK : MaterialModel::LINEAR;
  m.plane_stress = plane == 1;
  PetscCheck(std::isfinite(m.E) && m.E > 0, comm, PETSC_ERR_USER_INPUT,
             "-material_E %g is invalid; expected a finite Young's modulus > 0", m.E);
  PetscCheck(std::isfinite(m.nu) && m.nu > -1.0 && m.nu < 0.5, comm, PETSC_ERR_USER_INPUT,
             "-material_nu %g is invalid; expected a Poisson's ratio in (-1, 0.5)", m.nu);
  PetscCheck(std::isfinite(m.thickness) && m.thickness > 0, comm, PETSC_ERR_USER_INPUT,
             "-material_thickness %g is invalid; expected a finite thickness > 0", m.thickness);
  PetscFunctionReturn(0);
}

} // namespace signorini
