// The output directory's all-or-nothing switch: a run writes into DIR/incomplete/, publishing renames it to a run
// directory that DIR/current points to, and DIR's files link through current/ so that one rename replaces them all.
#include "signorini/io/output_directory.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>

namespace signorini {
namespace {

namespace fs = std::filesystem;

/// A fresh directory under the test's temporary directory, removed with everything in it at the end.
class OutputDirectoryTest : public ::testing::Test {
protected:
  void SetUp() override {
    root_ = fs::path(::testing::TempDir()) /
            ("signorini_output_directory_" + std::to_string(getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }

  static void Write(const fs::path &path, const std::string &text) { std::ofstream(path) << text; }
  static std::string Read(const fs::path &path) {
    std::ifstream f(path);
    return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  }
  /// The names of the entries of dir.
  static std::set<std::string> Entries(const fs::path &dir) {
    std::set<std::string> names;
    for (const auto &entry : fs::directory_iterator(dir)) names.insert(entry.path().filename().string());
    return names;
  }
  /// The names of dir's run directories (run_*).
  static std::set<std::string> Runs(const fs::path &dir) {
    std::set<std::string> runs;
    for (const std::string &name : Entries(dir))
      if (name.rfind("run_", 0) == 0) runs.insert(name);
    return runs;
  }
  /// Writes a run's files into DIR/incomplete/ as the run would, summary.json last.
  static void WriteRun(const fs::path &dir, const std::string &tag, bool with_nodes) {
    const fs::path staging = StagingDirectory(dir.string());
    Write(staging / "solution.h5", "h5 " + tag);
    Write(staging / "solution.xdmf", "xdmf " + tag);
    Write(staging / "body.xdmf", "body " + tag);
    if (with_nodes) Write(staging / "nodes.csv", "nodes " + tag);
    Write(staging / "summary.json", "summary " + tag);
  }

  fs::path root_;
};

TEST_F(OutputDirectoryTest, StagingIsIncompleteInsideDir) {
  EXPECT_EQ(fs::path(StagingDirectory("out/case")), fs::path("out/case") / "incomplete");
}

TEST_F(OutputDirectoryTest, PrepareMakesDirAndItsMissingParentsAndAnEmptyStaging) {
  const fs::path dir = root_ / "a" / "b" / "out";
  int made = -1;
  EXPECT_EQ(PrepareOutputDirectory(dir.string(), made), "");
  EXPECT_EQ(made, 3); // a, b and out
  EXPECT_TRUE(fs::is_directory(dir / "incomplete"));
  EXPECT_TRUE(fs::is_empty(dir / "incomplete"));
  // Prepared again: nothing made, a staging directory left by an interrupted run emptied.
  Write(dir / "incomplete" / "solution.h5", "half written");
  EXPECT_EQ(PrepareOutputDirectory(dir.string(), made), "");
  EXPECT_EQ(made, 0);
  EXPECT_TRUE(fs::is_empty(dir / "incomplete"));
}

TEST_F(OutputDirectoryTest, PublishLinksEveryFileThroughCurrentToOneRunDirectory) {
  const fs::path dir = root_ / "out";
  int made = 0;
  ASSERT_EQ(PrepareOutputDirectory(dir.string(), made), "");
  WriteRun(dir, "first", true);
  ASSERT_EQ(PublishOutputDirectory(dir.string()), "");
  const std::set<std::string> runs = Runs(dir);
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_FALSE(fs::exists(dir / "incomplete"));
  ASSERT_TRUE(fs::is_symlink(dir / "current"));
  EXPECT_EQ(fs::read_symlink(dir / "current"), fs::path(*runs.begin()));
  // Each file is a link to current/NAME, never to the run directory itself: the switch of current moves them all.
  for (const char *name : {"solution.h5", "solution.xdmf", "body.xdmf", "nodes.csv", "summary.json"}) {
    ASSERT_TRUE(fs::is_symlink(dir / name)) << name;
    EXPECT_EQ(fs::read_symlink(dir / name), fs::path("current") / name) << name;
  }
  EXPECT_EQ(Read(dir / "summary.json"), "summary first");
  EXPECT_EQ(Read(dir / "nodes.csv"), "nodes first");
  // Files the run did not write get no (dangling) link.
  EXPECT_FALSE(fs::exists(fs::symlink_status(dir / "obstacle.xdmf")));
  EXPECT_FALSE(fs::exists(fs::symlink_status(dir / "contact_boundary.xdmf")));
  EXPECT_EQ(Entries(dir), (std::set<std::string>{*runs.begin(), "current", "solution.h5", "solution.xdmf",
                                                 "body.xdmf", "nodes.csv", "summary.json"}));
}

TEST_F(OutputDirectoryTest, ASecondPublicationReplacesTheFirstWholeAndRemovesIt) {
  const fs::path dir = root_ / "out";
  int made = 0;
  ASSERT_EQ(PrepareOutputDirectory(dir.string(), made), "");
  WriteRun(dir, "first", true);
  ASSERT_EQ(PublishOutputDirectory(dir.string()), "");
  const std::string first = *Runs(dir).begin();
  // The second run is prepared and written beside the published first one, which stays readable meanwhile.
  ASSERT_EQ(PrepareOutputDirectory(dir.string(), made), "");
  EXPECT_EQ(Runs(dir), (std::set<std::string>{first}));
  WriteRun(dir, "second", false);
  EXPECT_EQ(Read(dir / "summary.json"), "summary first");
  ASSERT_EQ(PublishOutputDirectory(dir.string()), "");
  const std::set<std::string> runs = Runs(dir);
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_NE(*runs.begin(), first);
  EXPECT_EQ(fs::read_symlink(dir / "current"), fs::path(*runs.begin()));
  EXPECT_EQ(Read(dir / "summary.json"), "summary second");
  EXPECT_EQ(Read(dir / "solution.h5"), "h5 second");
  // nodes.csv of the first run is not left beside the second run's files.
  EXPECT_FALSE(fs::exists(fs::symlink_status(dir / "nodes.csv")));
}

TEST_F(OutputDirectoryTest, PrepareRemovesStaleRunsAndLinksButKeepsThePublishedRun) {
  const fs::path dir = root_ / "out";
  int made = 0;
  ASSERT_EQ(PrepareOutputDirectory(dir.string(), made), "");
  WriteRun(dir, "published", true);
  ASSERT_EQ(PublishOutputDirectory(dir.string()), "");
  const std::string published = *Runs(dir).begin();
  // What a run killed during its switch leaves: a renamed run directory that current does not point to, and a new
  // link not yet renamed over current.
  fs::create_directory(dir / "run_1_1");
  Write(dir / "run_1_1" / "summary.json", "stale");
  fs::create_symlink("run_1_1", dir / "current.new");
  Write(dir / "notes.txt", "the user's");
  ASSERT_EQ(PrepareOutputDirectory(dir.string(), made), "");
  EXPECT_EQ(Runs(dir), (std::set<std::string>{published}));
  EXPECT_FALSE(fs::exists(fs::symlink_status(dir / "current.new")));
  EXPECT_EQ(Read(dir / "summary.json"), "summary published");
  EXPECT_EQ(Read(dir / "notes.txt"), "the user's");
}

TEST_F(OutputDirectoryTest, APlainSummaryOfAnEarlierLayoutBecomesALink) {
  const fs::path dir = root_ / "out";
  fs::create_directories(dir);
  Write(dir / "summary.json", "old layout");
  Write(dir / "nodes.csv", "old layout");
  int made = 0;
  ASSERT_EQ(PrepareOutputDirectory(dir.string(), made), "");
  WriteRun(dir, "new", true);
  ASSERT_EQ(PublishOutputDirectory(dir.string()), "");
  for (const char *name : {"summary.json", "nodes.csv"}) {
    EXPECT_TRUE(fs::is_symlink(dir / name)) << name;
    EXPECT_EQ(Read(dir / name), std::string(name) == "summary.json" ? "summary new" : "nodes new");
  }
}

TEST_F(OutputDirectoryTest, ProblemNamesAFileInTheWayOrItsParent) {
  EXPECT_EQ(OutputDirectoryProblem((root_ / "fresh" / "deeper").string()), "");
  EXPECT_EQ(OutputDirectoryProblem(root_.string()), "");
  Write(root_ / "file", "x");
  const std::string file = (root_ / "file").string();
  EXPECT_EQ(OutputDirectoryProblem(file), "-output_dir '" + file + "' is not a directory; expected a writable directory");
  const std::string below = (root_ / "file" / "out").string();
  EXPECT_EQ(OutputDirectoryProblem(below),
            "-output_dir '" + below + "' (its parent '" + file + "') is not a directory; expected a writable directory");
  int made = 0;
  const std::string error = PrepareOutputDirectory(below, made);
  EXPECT_NE(error.find("-output_dir '" + below + "' cannot be created"), std::string::npos) << error;
}

} // namespace
} // namespace signorini
