// Validation of the -material_ options and the elastic constants derived from them.
#include "signorini/fem/material.hpp"

#include "petsc_helpers.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace signorini {
namespace {

using test::ErrorCapture;
using test::ScopedOptions;

PetscErrorCode ReadWith(const char *name, const char *value, Material &m, std::string *message = nullptr) {
  ScopedOptions options({{name, value}});
  ErrorCapture capture;
  const PetscErrorCode ierr = ReadMaterialOptions(PETSC_COMM_SELF, m);
  if (message) *message = capture.Message();
  return ierr;
}

TEST(MaterialOptions, DefaultsAreAccepted) {
  Material m;
  EXPECT_EQ(ReadMaterialOptions(PETSC_COMM_SELF, m), 0);
  EXPECT_EQ(m.model, MaterialModel::LINEAR);
  EXPECT_FALSE(m.plane_stress);
  EXPECT_EQ(m.E, 200.0);
  EXPECT_EQ(m.nu, 0.3);
  EXPECT_EQ(m.thickness, 1.0);
}

TEST(MaterialOptions, GoodValuesAreRead) {
  ScopedOptions options({{"-material_E", "1e3"},
                         {"-material_nu", "-0.2"},
                         {"-material_thickness", "0.25"},
                         {"-material_model", "svk"},
                         {"-material_plane", "stress"}});
  Material m;
  const double before = test::PetscMemoryInUse();
  ASSERT_EQ(ReadMaterialOptions(PETSC_COMM_SELF, m), 0);
  EXPECT_EQ(test::PetscMemoryInUse(), before);
  EXPECT_EQ(m.E, 1e3);
  EXPECT_EQ(m.nu, -0.2);
  EXPECT_EQ(m.thickness, 0.25);
  EXPECT_EQ(m.model, MaterialModel::SVK);
  EXPECT_TRUE(m.plane_stress);
  EXPECT_STREQ(m.ModelName(), "svk");
}

TEST(MaterialOptions, NearlyIncompressibleAndAuxeticLimitsInsideTheRangeAreAccepted) {
  for (const char *nu : {"0.4999", "-0.999", "0"}) {
    SCOPED_TRACE(nu);
    Material m;
    EXPECT_EQ(ReadWith("-material_nu", nu, m), 0);
    EXPECT_EQ(m.nu, std::stod(nu));
  }
}

TEST(MaterialOptions, BadYoungsModulusIsRejected) {
  for (const char *E : {"0", "-5", "nan", "inf", "0x10", "", "1e-300", "1e300"}) {
    SCOPED_TRACE(E);
    Material m;
    std::string message;
    EXPECT_NE(ReadWith("-material_E", E, m, &message), 0);
    EXPECT_NE(message.find("-material_E"), std::string::npos) << message;
  }
}

TEST(MaterialOptions, PoissonRatioOutsideTheOpenIntervalIsRejected) {
  for (const char *nu : {"0.5", "0.7", "-1", "-1.5", "nan"}) {
    SCOPED_TRACE(nu);
    Material m;
    std::string message;
    EXPECT_NE(ReadWith("-material_nu", nu, m, &message), 0);
    EXPECT_NE(message.find("-material_nu"), std::string::npos) << message;
  }
}

TEST(MaterialOptions, BadThicknessIsRejected) {
  for (const char *t : {"0", "-1", "nan", "inf", "", "1e-300"}) {
    SCOPED_TRACE(t);
    Material m;
    std::string message;
    EXPECT_NE(ReadWith("-material_thickness", t, m, &message), 0);
    EXPECT_NE(message.find("-material_thickness"), std::string::npos) << message;
  }
}

TEST(MaterialOptions, StiffnessScaleNamesBothInputsAndItsBounds) {
  ScopedOptions options({{"-material_E", "1e-4"}, {"-material_thickness", "1e-3"}});
  ErrorCapture capture;
  Material m;
  EXPECT_NE(ReadMaterialOptions(PETSC_COMM_SELF, m), 0);
  for (const char *want : {"-material_E 0.0001", "-material_thickness 0.001", "1e-07", "[1e-06, 1e+24]"})
    EXPECT_NE(capture.Message().find(want), std::string::npos) << capture.Message();
}

TEST(MaterialOptions, StiffnessScaleBoundsAreAccepted) {
  for (const auto &[E, t] : {std::pair<const char *, const char *>{"1e-6", "1"}, {"1e12", "1e12"}}) {
    ScopedOptions options({{"-material_E", E}, {"-material_thickness", t}});
    Material m;
    EXPECT_EQ(ReadMaterialOptions(PETSC_COMM_SELF, m), 0) << E << " " << t;
  }
}

TEST(MaterialOptions, UnknownModelOrPlaneAndNonNumbersAreRejected) {
  Material m;
  EXPECT_NE(ReadWith("-material_model", "neohookean", m), 0);
  EXPECT_NE(ReadWith("-material_plane", "shell", m), 0);
  EXPECT_NE(ReadWith("-material_model", "", m), 0);
  EXPECT_NE(ReadWith("-material_E", "2e11Pa", m), 0);
}

TEST(Material, DerivedConstants) {
  Material m;
  m.E = 260.0;
  m.nu = 0.3;
  EXPECT_DOUBLE_EQ(m.Mu(), 100.0);
  EXPECT_DOUBLE_EQ(m.Lambda3D(), 150.0);
  EXPECT_DOUBLE_EQ(m.LambdaPlane(), 150.0);
  m.plane_stress = true;
  // Plane stress: lambda* = 2 lambda mu / (lambda + 2 mu) = E nu / (1 - nu^2).
  EXPECT_DOUBLE_EQ(m.LambdaPlane(), 260.0 * 0.3 / (1 - 0.09));
}

} // namespace
} // namespace signorini
