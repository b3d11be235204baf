// Strict option readers: empty values, hexadecimal, overflow and out-of-range values are errors naming the option.
#include "signorini/options/readers.hpp"
#include "signorini/options/command_line.hpp"
#include "signorini/options/options_files.hpp"
#include "signorini/options/unused_options.hpp"

#include "petsc_helpers.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace signorini {
namespace {

using test::ErrorCapture;
using test::ScopedOptions;

const RealRange GAP{0, 1e-3, false, false, 20, "body diagonal"};

PetscErrorCode ReadReal(double &value, PetscBool *set = nullptr) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_SELF, nullptr, "test", "");
  PetscCall(OptionsReal(PetscOptionsObject, "-test_gap", "gap", GAP, value, set));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

PetscErrorCode ReadInt(PetscInt &value) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_SELF, nullptr, "test", "");
  PetscCall(OptionsInt(PetscOptionsObject, "-test_steps", "steps", 1, 10000, value));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

PetscErrorCode ReadList(std::vector<double> &values, PetscBool *set) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_SELF, nullptr, "test", "");
  PetscCall(OptionsRealList(PetscOptionsObject, "-test_list", "list", "no obstacle", "X,Y", values, set));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

/// Runs read with option name set to value; returns the error message ("" when it succeeded).
template <class Read> std::string MessageOf(const char *name, const char *value, Read read) {
  ScopedOptions options({{name, value}});
  ErrorCapture capture;
  const PetscErrorCode ierr = read();
  EXPECT_EQ(ierr != 0, !capture.Message().empty()) << capture.Message();
  return capture.Message();
}

TEST(RealRange, DescribesItsBoundsRelativeAndAbsolute) {
  EXPECT_EQ(GAP.Relative(), "[0, 0.001] x body diagonal");
  EXPECT_EQ(GAP.Absolute(), "[0, 0.02] ([0, 0.001] x body diagonal, body diagonal 20)");
  EXPECT_EQ((RealRange{0, 1, false, true}).Absolute(), "[0, 1)");
  EXPECT_TRUE(GAP.Contains(0.02));
  EXPECT_FALSE(GAP.Contains(0.0201));
  EXPECT_FALSE((RealRange{0, 1, true, true}).Contains(0));
}

TEST(OptionsReal, ReadsValuesInsideTheRangeAndLeavesTheDefaultWhenUnset) {
  double value = 1e-9;
  PetscBool set = PETSC_TRUE;
  EXPECT_EQ(ReadReal(value, &set), 0);
  EXPECT_EQ(value, 1e-9);
  EXPECT_FALSE(set);
  ScopedOptions options({{"-test_gap", "2e-2"}});
  const double before = test::PetscMemoryInUse();
  EXPECT_EQ(ReadReal(value, &set), 0);
  EXPECT_EQ(test::PetscMemoryInUse(), before);
  EXPECT_EQ(value, 0.02);
  EXPECT_TRUE(set);
}

TEST(OptionsReal, EmptyHexNonFiniteAndOutOfRangeValuesAreErrorsNamingOptionValueAndRange) {
  const struct {
    const char *value, *expected;
  } cases[] = {{"", "-test_gap is given without a value"},
               {"0x10", "-test_gap 0x10 is invalid"},
               {"nan", "-test_gap nan is invalid"},
               {"1e400", "-test_gap 1e400 is invalid"},
               {"1e300", "-test_gap 1e300 is out of range"},
               {"-1e-12", "-test_gap -1e-12 is out of range"}};
  for (const auto &c : cases) {
    double value = 1e-9;
    const std::string message = MessageOf("-test_gap", c.value, [&] { return ReadReal(value); });
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
    EXPECT_NE(message.find("[0, 0.02] ([0, 0.001] x body diagonal, body diagonal 20)"), std::string::npos) << message;
    EXPECT_EQ(value, 1e-9);
  }
}

TEST(OptionsInt, ReadsIntegersExactlyInsideTheRange) {
  PetscInt value = 1;
  ScopedOptions options({{"-test_steps", "10000"}});
  EXPECT_EQ(ReadInt(value), 0);
  EXPECT_EQ(value, 10000);
}

TEST(OptionsInt, OverflowOutOfRangeAndNonIntegersRepeatTheValueAsWritten) {
  for (const char *text : {"99999999999999999999", "1000000000", "10001", "0", "-1", "1.5", "1e3", "0x10"}) {
    PetscInt value = 1;
    const std::string message = MessageOf("-test_steps", text, [&] { return ReadInt(value); });
    EXPECT_NE(message.find(std::string("-test_steps ") + text + " is invalid; expected an integer in [1, 10000]"),
              std::string::npos)
        << message;
    EXPECT_EQ(value, 1);
  }
  PetscInt value = 1;
  EXPECT_NE(MessageOf("-test_steps", "", [&] { return ReadInt(value); }).find("-test_steps is given without a value"),
            std::string::npos);
}

TEST(OptionsRealList, ReadsEveryItemStrictly) {
  std::vector<double> values;
  PetscBool set = PETSC_FALSE;
  ScopedOptions options({{"-test_list", "1, -2.5e1,.5 "}});
  EXPECT_EQ(ReadList(values, &set), 0);
  EXPECT_TRUE(set);
  EXPECT_EQ(values, (std::vector<double>{1, -25, 0.5}));
}

TEST(OptionsRealList, EmptyListsEmptyItemsAndBadNumbersAreErrors) {
  const struct {
    const char *value, *expected;
  } cases[] = {{"", "-test_list is given without a value, which would leave no obstacle"},
               {",", "-test_list , has an empty item 1"},
               {"1,,2", "-test_list 1,,2 has an empty item 2"},
               {"1, ,2", "-test_list 1, ,2 has an empty item 2"},
               {"1,0x10", "-test_list 1,0x10: value 2 '0x10' is invalid"},
               {"1,inf", "-test_list 1,inf: value 2 'inf' is invalid"}};
  for (const auto &c : cases) {
    std::vector<double> values;
    PetscBool set;
    const std::string message = MessageOf("-test_list", c.value, [&] { return ReadList(values, &set); });
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
  }
}

/// CheckCommandLine on the words of a command line; returns the error message ("" when it passed).
std::string CommandLineMessage(std::vector<std::string> words) {
  words.insert(words.begin(), "signorini");
  std::vector<char *> argv;
  for (std::string &w : words) argv.push_back(w.data());
  ErrorCapture capture;
  const PetscErrorCode ierr = CheckCommandLine((int)argv.size(), argv.data());
  EXPECT_EQ(ierr != 0, !capture.Message().empty()) << capture.Message();
  return capture.Message();
}

TEST(CheckCommandLine, AnOptionGivenTwiceIsAnErrorNamingItAndBothValues) {
  EXPECT_EQ(CommandLineMessage({"-material_E", "300", "-material_nu", "0.3", "-contact_monitor"}), "");
  EXPECT_EQ(CommandLineMessage({"-options_file", "a.yml", "-options_file", "b.yml", "-material_E", "3"}), "");
  const struct {
    std::vector<std::string> words;
    const char *expected;
  } cases[] = {{{"-material_E", "300", "-material_E", "400"}, "option -material_E is given twice on the command line "
                                                              "(300, then 400)"},
               {{"-bc_traction", "top:0:-0.625", "-load_steps", "2", "-bc_traction", "top:0:-1"},
                "option -bc_traction is given twice on the command line (top:0:-0.625, then top:0:-1)"},
               {{"-contact_monitor", "-Contact_Monitor"}, "option -Contact_Monitor is given twice"},
               {{"-contact_max_it", "5", "-prefix_push", "contact_", "-max_it", "6", "-prefix_pop"},
                "option -contact_max_it is given twice on the command line (5, then 6)"}};
  for (const auto &c : cases) {
    const std::string message = CommandLineMessage(c.words);
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
  }
}

TEST(OptionsFileProblem, AnOptionSetInTwoYamlDocumentsIsSetTwice) {
  const std::string path = ::testing::TempDir() + "/signorini_two_documents.yml";
  const auto problem_of = [&](const char *text) {
    std::ofstream(path) << text;
    std::string files;
    std::vector<std::string> words = {"signorini", "-options_file", path};
    std::vector<char *> argv;
    for (std::string &w : words) argv.push_back(w.data());
    return OptionsFileProblem((int)argv.size(), argv.data(), files);
  };
  EXPECT_EQ(problem_of("material_E: 1\n---\nmaterial_nu: 0.3\n"), "");
  std::string problem = problem_of("material_E: 1\n---\nmaterial:\n  E: 5\n");
  EXPECT_NE(problem.find("line 4: option -material_E is set again (first on line 1)"), std::string::npos) << problem;
  // A merge in one document overrides nothing of the next.
  problem = problem_of("base: &b {material_E: 1}\ncase:\n  <<: *b\n---\ncase_material_E: 2\n");
  EXPECT_NE(problem.find("option -case_material_E is set again"), std::string::npos) << problem;
  std::remove(path.c_str());
}


PetscErrorCode ReadString(std::string &value) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_SELF, nullptr, "test", "");
  PetscCall(OptionsString(PetscOptionsObject, "-test_groups_file", "file", "a file name", value));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

PetscErrorCode ReadStrings(std::vector<std::string> &items) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_SELF, nullptr, "test", "");
  PetscCall(OptionsStringList(PetscOptionsObject, "-test_groups", "groups", "no contact", "GROUP,GROUP,...", items));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

PetscErrorCode RequireValue() {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_SELF, nullptr, "test", "");
  PetscCall(OptionsRequireValue(PetscOptionsObject, "-test_type", "linear or svk"));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

TEST(OptionsString, ReadsTheValueAndRefusesTheNameAlone) {
  std::string value = "default";
  EXPECT_EQ(MessageOf("-test_groups_file", "groups.txt", [&] { return ReadString(value); }), "");
  EXPECT_EQ(value, "groups.txt");
  EXPECT_EQ(MessageOf("-test_groups_file", "", [&] { return ReadString(value); }),
            "-test_groups_file is given without a value; expected a file name");
  EXPECT_EQ(MessageOf("-test_type", "", RequireValue), "-test_type is given without a value; expected linear or svk");
  EXPECT_EQ(MessageOf("-test_type", "svk", RequireValue), "");
}

TEST(OptionsStringList, TrimsBlanksAroundItemsAndRefusesEmptyOnesSayingWhatEmptyWouldLeave) {
  std::vector<std::string> items;
  EXPECT_EQ(MessageOf("-test_groups", "bottom, left ,right", [&] { return ReadStrings(items); }), "");
  EXPECT_EQ(items, (std::vector<std::string>{"bottom", "left", "right"}));
  EXPECT_EQ(MessageOf("-test_groups", "", [&] { return ReadStrings(items); }),
            "-test_groups is given without a value, which would leave no contact; expected GROUP,GROUP,...");
  EXPECT_EQ(MessageOf("-test_groups", "bottom, ,right", [&] { return ReadStrings(items); }),
            "-test_groups bottom, ,right has an empty item 2 (an empty list would leave no contact); expected "
            "GROUP,GROUP,...");
}

/// The error message of CheckRealValue on raw ("" when it passed).
std::string CheckRealMessage(const char *raw, const RealRange &range, double &value) {
  ErrorCapture capture;
  const PetscErrorCode ierr = CheckRealValue(PETSC_COMM_SELF, "-contact_ksp_rtol", raw, range, value);
  EXPECT_EQ(ierr != 0, !capture.Message().empty()) << capture.Message();
  return capture.Message();
}

TEST(CheckRealValue, ChecksTextThatPetscReadsItselfAsOptionsRealDoes) {
  const RealRange open{0, 1, true, true};
  double value = 0;
  EXPECT_EQ(CheckRealMessage("1e-8", open, value), "");
  EXPECT_EQ(value, 1e-8);
  EXPECT_EQ(CheckRealMessage("", open, value), "-contact_ksp_rtol is given without a value; expected a number in (0, 1)");
  for (const char *raw : {"0x1p-3", "nan", "1e-8x"}) {
    const std::string message = CheckRealMessage(raw, open, value);
    EXPECT_EQ(message.rfind(std::string("-contact_ksp_rtol ") + raw + " is invalid; expected", 0), 0u) << message;
    EXPECT_NE(message.find(" in (0, 1)"), std::string::npos) << message;
  }
  EXPECT_EQ(CheckRealMessage("1", open, value), "-contact_ksp_rtol 1 is out of range; expected a number in (0, 1)");
  EXPECT_EQ(CheckRealMessage("2.5", RealRange::Whole(1, 1e9), value),
            "-contact_ksp_rtol 2.5 is not a whole number; expected a whole number in [1, 1e+09]");
  EXPECT_EQ(value, 1e-8); // a refused value leaves it
  EXPECT_EQ(CheckRealMessage("1000000000", RealRange::Whole(1, 1e9), value), "");
  EXPECT_EQ(value, 1e9);
}

TEST(IsSolverOption, NamesTheSaddlePointSolversOptionsOnly) {
  for (const char *name : {"contact_ksp_type", "contact_pc_factor_mat_solver_type", "contact_mat_mumps_icntl_14",
                           "contact_fieldsplit_0_pc_type", "contact_sub_pc_type", "contact_mg_levels_ksp_type"})
    EXPECT_TRUE(IsSolverOption(name)) << name;
  for (const char *name : {"contact_max_it", "contact_monitor", "contact_kept_solver", "ksp_type", "pc_type",
                           "material_ksp_type", "contact_kspx", "contact_"})
    EXPECT_FALSE(IsSolverOption(name)) << name;
}

TEST(CheckCommandLine, AStrayWordOrAMisspeltOptionsFileIsAnErrorNamingIt) {
  EXPECT_EQ(CommandLineMessage({"options/hertz.yml"}),
            "unexpected argument 'options/hertz.yml': every input is an option, -name value; to read this case file, "
            "give -options_file options/hertz.yml");
  EXPECT_EQ(CommandLineMessage({"-material_E", "3", "extra"}),
            "unexpected argument 'extra': every input is an option, -name value");
  EXPECT_EQ(CommandLineMessage({"-option_file", "options/hertz.yml"}),
            "unknown option -option_file; expected -options_file FILE");
  EXPECT_EQ(CommandLineMessage({"-options_files", "options/hertz.yml"}),
            "unknown option -options_files; expected -options_file FILE");
}

TEST(OptionsFileProblem, AMissingFileOrADirectoryIsNamedWithWhatWasExpected) {
  const auto problem_of = [](const std::string &path) {
    std::string files;
    std::vector<std::string> words = {"signorini", "-options_file", path};
    std::vector<char *> argv;
    for (std::string &w : words) argv.push_back(w.data());
    return OptionsFileProblem((int)argv.size(), argv.data(), files);
  };
  const std::string missing = ::testing::TempDir() + "signorini_no_such_options.yml";
  std::remove(missing.c_str());
  EXPECT_EQ(problem_of(missing),
            "-options_file " + missing + ": no such file; expected a readable YAML or PETSc options file");
  const std::string directory = ::testing::TempDir();
  EXPECT_EQ(problem_of(directory),
            "-options_file " + directory + ": it is a directory; expected a readable YAML or PETSc options file");
}

} // namespace
} // namespace signorini
