// Parsing of Dirichlet and load entries, and the -bc_ options.
#include "signorini/bc/boundary_conditions.hpp"

#include "petsc_helpers.hpp"

#include <gtest/gtest.h>

namespace signorini {
namespace {

using test::ErrorCapture;
using test::ScopedOptions;

void ExpectSpec(const DirichletSpec &s, const std::string &group, int component, double value) {
  EXPECT_EQ(s.group, group);
  EXPECT_EQ(s.component, component);
  EXPECT_EQ(s.value, value);
}

TEST(ParseDirichlet, ComponentWithoutValueDefaultsToZero) {
  std::vector<DirichletSpec> out;
  EXPECT_EQ(ParseDirichlet("left:x", 2, out), "");
  ASSERT_EQ(out.size(), 1u);
  ExpectSpec(out[0], "left", 0, 0.0);
}

TEST(ParseDirichlet, SeveralLettersShareOneValue) {
  std::vector<DirichletSpec> out;
  EXPECT_EQ(ParseDirichlet("left:xy=0.5", 2, out), "");
  ASSERT_EQ(out.size(), 2u);
  ExpectSpec(out[0], "left", 0, 0.5);
  ExpectSpec(out[1], "left", 1, 0.5);
}

TEST(ParseDirichlet, SeveralFieldsAppendToTheList) {
  std::vector<DirichletSpec> out;
  EXPECT_EQ(ParseDirichlet("bottom:y", 2, out), "");
  EXPECT_EQ(ParseDirichlet("top:x=0:y=-0.1", 2, out), "");
  ASSERT_EQ(out.size(), 3u);
  ExpectSpec(out[0], "bottom", 1, 0.0);
  ExpectSpec(out[1], "top", 0, 0.0);
  ExpectSpec(out[2], "top", 1, -0.1);
}

TEST(ParseDirichlet, ZIsAComponentIn3DOnly) {
  std::vector<DirichletSpec> out;
  EXPECT_EQ(ParseDirichlet("base:z=2e-3", 3, out), "");
  ASSERT_EQ(out.size(), 1u);
  ExpectSpec(out[0], "base", 2, 2e-3);
  const std::string error = ParseDirichlet("base:z", 2, out);
  EXPECT_NE(error.find("'z'"), std::string::npos) << error;
  EXPECT_NE(error.find("2D"), std::string::npos) << error;
}

TEST(ParseDirichlet, MalformedEntriesAreRejected) {
  for (const char *entry : {"left", ":x", ":x=0", "left:", "left::y", "left:=1", "left:q", "left:X",
                            "left:x=", "left:x=abc", "left:x=0.1mm", "left:x=nan", "left:x=inf", "left:x=-inf",
                            "left:x=1e999", "left:x=1=2", "left:x=0:y=nan", ""}) {
    std::vector<DirichletSpec> out;
    const std::string error = ParseDirichlet(entry, 2, out);
    EXPECT_NE(error, "") << "'" << entry << "'";
    if (*entry) {
      EXPECT_NE(error.find(entry), std::string::npos) << "the message quotes the entry: " << error;
    }
  }
}

TEST(ParseLoad, ReadsExactlyCountNumbers) {
  LoadSpec spec;
  EXPECT_EQ(ParseLoad("top:0:-1.5", 2, "-bc_traction", spec), "");
  EXPECT_EQ(spec.group, "top");
  EXPECT_EQ(spec.value, (std::vector<double>{0.0, -1.5}));
  EXPECT_EQ(ParseLoad("contact:2.5e2", 1, "-bc_pressure", spec), "");
  EXPECT_EQ(spec.group, "contact");
  EXPECT_EQ(spec.value, (std::vector<double>{250.0}));
}

TEST(ParseLoad, WrongCountOfNumbersIsRejected) {
  LoadSpec spec;
  std::string error = ParseLoad("top:1", 2, "-bc_traction", spec);
  EXPECT_NE(error.find("1 value(s)"), std::string::npos) << error;
  EXPECT_NE(error.find("-bc_traction"), std::string::npos) << error;
  error = ParseLoad("top:1:2:3", 2, "-bc_traction", spec);
  EXPECT_NE(error.find("3 value(s)"), std::string::npos) << error;
  EXPECT_NE(ParseLoad("top:1:2", 1, "-bc_pressure", spec), "");
  EXPECT_NE(ParseLoad("top", 1, "-bc_pressure", spec), "");
}

TEST(ParseLoad, MissingGroupAndBadNumbersAreRejected) {
  for (const char *entry : {":0:1", "top:x:1", "top:nan:0", "top:0:inf", "top:0:", "top::1", "top:1e999:0", ""}) {
    LoadSpec spec;
    EXPECT_NE(ParseLoad(entry, 2, "-bc_point_force", spec), "") << "'" << entry << "'";
  }
}

TEST(BoundaryConditionOptions, AllKindsAreRead) {
  ScopedOptions options({{"-bc_dirichlet", "left:xy,bottom:y=-0.01"},
                         {"-bc_traction", "right:1:0"},
                         {"-bc_pressure", "top:3,tip:4"},
                         {"-bc_point_force", "tip:0:-1"},
                         {"-bc_body_force", "0,-9.81"}});
  BoundaryConditions bc;
  const double before = test::PetscMemoryInUse();
  ASSERT_EQ(ReadBoundaryConditions(PETSC_COMM_SELF, 2, bc), 0);
  EXPECT_EQ(test::PetscMemoryInUse(), before);
  ASSERT_EQ(bc.dirichlet.size(), 3u);
  ExpectSpec(bc.dirichlet[2], "bottom", 1, -0.01);
  ASSERT_EQ(bc.traction.size(), 1u);
  EXPECT_EQ(bc.traction[0].value, (std::vector<double>{1.0, 0.0}));
  ASSERT_EQ(bc.pressure.size(), 2u);
  EXPECT_EQ(bc.pressure[1].group, "tip");
  EXPECT_EQ(bc.pressure[1].value, (std::vector<double>{4.0}));
  ASSERT_EQ(bc.point_force.size(), 1u);
  EXPECT_EQ(bc.body_force, (std::vector<double>{0.0, -9.81}));
}

TEST(BoundaryConditionOptions, BadEntriesAreErrorsNamingTheOption) {
  const struct {
    const char *option, *value;
  } cases[] = {
      {"-bc_dirichlet", "left:z"}, {"-bc_dirichlet", "left:x,:y"}, {"-bc_traction", "right:1"},
      {"-bc_pressure", "top:1:2"}, {"-bc_point_force", "tip:a:b"}, {"-bc_body_force", "0,-9.81,1"},
  };
  for (const auto &c : cases) {
    SCOPED_TRACE(std::string(c.option) + " " + c.value);
    ScopedOptions options({{c.option, c.value}});
    ErrorCapture capture;
    BoundaryConditions bc;
    EXPECT_NE(ReadBoundaryConditions(PETSC_COMM_SELF, 2, bc), 0);
    EXPECT_NE(capture.Message().find(c.option), std::string::npos) << capture.Message();
  }
}

} // namespace
} // namespace signorini
