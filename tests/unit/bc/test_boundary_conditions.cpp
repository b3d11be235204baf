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

TEST(Ramp, ClampsBetweenItsEnds) {
  const Ramp ramp{0.25, 0.75};
  EXPECT_EQ(ramp.At(0.0), 0.0);
  EXPECT_EQ(ramp.At(0.25), 0.0);
  EXPECT_EQ(ramp.At(0.5), 0.5);
  EXPECT_EQ(ramp.At(0.75), 1.0);
  EXPECT_EQ(ramp.At(1.0), 1.0);
  EXPECT_EQ(ramp.Suffix(), "@0.25:0.75");
}

TEST(Ramp, TheDefaultIsTheLoadFactorItself) {
  const Ramp ramp;
  EXPECT_TRUE(ramp.Proportional());
  EXPECT_EQ(ramp.Suffix(), "");
  for (double t : {0.0, 0.1, 1.0 / 3.0, 0.7, 1.0}) EXPECT_EQ(ramp.At(t), t);
}

TEST(ParseRamp, SplitsTheSuffixOff) {
  std::string rest;
  Ramp ramp{0.5, 1};
  EXPECT_EQ(ParseRamp("top:1:0", rest, ramp), "");
  EXPECT_EQ(rest, "top:1:0");
  EXPECT_TRUE(ramp.Proportional());
  EXPECT_EQ(ParseRamp("left:x=0:y=0.02@0.2:1", rest, ramp), "");
  EXPECT_EQ(rest, "left:x=0:y=0.02");
  EXPECT_EQ(ramp, (Ramp{0.2, 1}));
  std::vector<DirichletSpec> out;
  EXPECT_EQ(ParseDirichlet("left:x=0:y=0.02@0.2:1", 2, out), "");
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].ramp, (Ramp{0.2, 1}));
  EXPECT_EQ(out[1].ramp, (Ramp{0.2, 1}));
  LoadSpec load;
  EXPECT_EQ(ParseLoad("top:5@0:0.5", 1, "-bc_pressure", load), "");
  EXPECT_EQ(load.value, (std::vector<double>{5.0}));
  EXPECT_EQ(load.ramp, (Ramp{0, 0.5}));
}

TEST(ParseRamp, MalformedRampsAreRejected) {
  for (const char *entry : {"top:1@", "top:1@0.5", "top:1@a:1", "top:1@0:1:2", "top:1@0.5:0.5", "top:1@0.6:0.2",
                            "top:1@-0.1:1", "top:1@0:1.5", "top:1@0:0.5@0.5:1", "top:1@0:nan", "top:1@:1"}) {
    std::string rest;
    Ramp ramp;
    const std::string error = ParseRamp(entry, rest, ramp);
    EXPECT_NE(error.find(std::string("'") + entry + "'"), std::string::npos) << error;
    EXPECT_NE(error.find("expected one suffix @T0:T1"), std::string::npos) << error;
  }
}

TEST(AnyRampMoves, OnlyItemsWithAValueWhoseShareChanges) {
  BoundaryConditions bc;
  bc.dirichlet.push_back({"left", 0, 0.0, "left:x", Ramp{}});
  EXPECT_FALSE(AnyRampMoves(bc, 0, 0.5)); // a support: 0 at any time
  bc.pressure.push_back({"top", {2.0}, "top:2@0.5:1", Ramp{0.5, 1}});
  EXPECT_FALSE(AnyRampMoves(bc, 0, 0.5));
  EXPECT_TRUE(AnyRampMoves(bc, 0.5, 0.75));
  bc.body_force = {0, -1};
  bc.body_force_ramp = Ramp{0, 0.25};
  EXPECT_TRUE(AnyRampMoves(bc, 0, 0.5));
  EXPECT_FALSE(AnyRampMoves(bc, 0.25, 0.5));
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
  EXPECT_TRUE(bc.body_force_ramp.Proportional());
}

TEST(BoundaryConditionOptions, RampsAreRead) {
  ScopedOptions options({{"-bc_dirichlet", "left:x=0.01@0.5:1"},
                         {"-bc_traction", "right:1:0@0.5:1"},
                         {"-bc_pressure", "top:3@0:0.5,tip:4"},
                         {"-bc_body_force", "0,-9.81@0:0.5"}});
  BoundaryConditions bc;
  ASSERT_EQ(ReadBoundaryConditions(PETSC_COMM_SELF, 2, bc), 0);
  ASSERT_EQ(bc.dirichlet.size(), 1u);
  EXPECT_EQ(bc.dirichlet[0].ramp, (Ramp{0.5, 1}));
  EXPECT_EQ(bc.traction[0].ramp, (Ramp{0.5, 1}));
  EXPECT_EQ(bc.pressure[0].ramp, (Ramp{0, 0.5}));
  EXPECT_TRUE(bc.pressure[1].ramp.Proportional());
  EXPECT_EQ(bc.body_force, (std::vector<double>{0.0, -9.81}));
  EXPECT_EQ(bc.body_force_ramp, (Ramp{0, 0.5}));
}

TEST(BoundaryConditionOptions, BadEntriesAreErrorsNamingTheOption) {
  const struct {
    const char *option, *value;
  } cases[] = {
      {"-bc_dirichlet", "left:z"}, {"-bc_dirichlet", "left:x,:y"}, {"-bc_traction", "right:1"},
      {"-bc_pressure", "top:1:2"}, {"-bc_point_force", "tip:a:b"}, {"-bc_body_force", "0,-9.81,1"},
      {"-bc_pressure", "top:1@1:0"}, {"-bc_dirichlet", "left:x@0:2"}, {"-bc_body_force", "0,-9.81@"},
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
