// Which options file last set an option (plain and YAML files, layered, overridden by the command line), and where a
// relative path is looked for.
#include "signorini/options/option_paths.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace signorini {
namespace {

class OptionPathsTest : public ::testing::Test {
protected:
  void SetUp() override {
    char pattern[] = "/tmp/signorini_option_paths_XXXXXX";
    ASSERT_NE(mkdtemp(pattern), nullptr);
    dir_ = pattern;
    Write("case.yml", "# a case\nmesh_file: ../meshes/a.msh\nmaterial_E: 100\n");
    Write("solver.yml", "contact_ksp_type: preonly\n");
    Write("plain.txt", "-material_nu 0.2\n-mesh_file b.msh # comment\n");
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  void Write(const std::string &name, const std::string &text) { std::ofstream(dir_ + "/" + name) << text; }
  std::string Last(const std::vector<std::string> &args, const char *env = nullptr) {
    std::string file;
    EXPECT_EQ(LastOptionsFileSetting(args, env, "-mesh_file", file), 0);
    return file;
  }
  std::string dir_;
};

TEST_F(OptionPathsTest, FileThatSetsTheOptionLast) {
  const std::string yml = dir_ + "/case.yml", plain = dir_ + "/plain.txt", solver = dir_ + "/solver.yml";
  EXPECT_EQ(Last({"-options_file", yml}), yml);
  EXPECT_EQ(Last({"-options_file", plain}), plain);
  // A later file that does not set it leaves the earlier one in charge; a later one that does takes over.
  EXPECT_EQ(Last({"-options_file", yml, "-options_file", solver}), yml);
  EXPECT_EQ(Last({"-options_file", yml, "-options_file", plain}), plain);
  EXPECT_EQ(Last({"-options_file", plain, "-options_file", yml}), yml);
  EXPECT_EQ(Last({"-options_file_yaml", yml}), yml);
}

TEST_F(OptionPathsTest, CommandLineAfterAFileWins) {
  const std::string yml = dir_ + "/case.yml";
  EXPECT_EQ(Last({"-options_file", yml, "-mesh_file", "x.msh"}), "");
  EXPECT_EQ(Last({"-mesh_file", "x.msh", "-options_file", yml}), yml);
  EXPECT_EQ(Last({"-material_E", "3"}), "");
  // PETSC_OPTIONS comes before the command line.
  EXPECT_EQ(Last({}, ("-options_file " + yml).c_str()), yml);
  EXPECT_EQ(Last({"-mesh_file", "x.msh"}, ("-options_file " + yml).c_str()), "");
}

TEST_F(OptionPathsTest, FirstExistingNamesEveryPlaceLooked) {
  PathCandidates c;
  c.paths = {dir_ + "/nothing.msh", dir_ + "/case.yml"};
  c.origins = {"relative to options file 'o.yml'", "relative to the current directory"};
  std::string looked;
  EXPECT_EQ(FirstExisting(c, looked), dir_ + "/case.yml");
  EXPECT_TRUE(looked.empty());
  c.paths[1] = dir_ + "/missing.msh";
  EXPECT_EQ(FirstExisting(c, looked), "");
  EXPECT_NE(looked.find("nothing.msh' (relative to options file 'o.yml') nor at '"), std::string::npos) << looked;
  EXPECT_NE(looked.find("missing.msh' (relative to the current directory)"), std::string::npos) << looked;
}

TEST(OptionPaths, AbsolutePathIsItsOnlyCandidate) {
  PathCandidates c;
  ASSERT_EQ(PathCandidatesFor("-mesh_file", "/abs/m.msh", c), 0);
  ASSERT_EQ(c.paths.size(), 1u);
  EXPECT_EQ(c.paths[0], "/abs/m.msh");
}

} // namespace
} // namespace signorini
