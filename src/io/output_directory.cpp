// The all-or-nothing switch of an output directory through one rename of the DIR/current link.
#include "signorini/io/output_directory.hpp"

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>

namespace signorini {

namespace fs = std::filesystem;

namespace {

constexpr const char *STAGING = "incomplete";
constexpr const char *CURRENT = "current";
constexpr const char *RUN_PREFIX = "run_";

/// The run directory DIR/current points to, or an empty path.
fs::path CurrentRun(const fs::path &dir) {
  std::error_code ec;
  const fs::path target = fs::read_symlink(dir / CURRENT, ec);
  return ec ? fs::path() : target.filename();
}

/// Replaces `link` by a symbolic link to `target` with one rename (atomic on POSIX file systems).
std::string ReplaceLink(const fs::path &link, const fs::path &target) {
  std::error_code ec;
  const fs::path tmp = link.string() + ".new";
  fs::remove(tmp, ec);
  fs::create_symlink(target, tmp, ec);
  if (!ec) fs::rename(tmp, link, ec);
  return ec ? "cannot link '" + link.string() + "' to '" + target.string() + "': " + ec.message() : "";
}

} // namespace

std::string StagingDirectory(const std::string &dir) { return (fs::path(dir) / STAGING).string(); }

std::string OutputDirectoryProblem(const std::string &dir_name) {
  std::error_code ec;
  const fs::path requested = fs::absolute(fs::path(dir_name), ec);
  if (ec)
    return "-output_dir '" + dir_name + "' is not a usable path (" + ec.message() + "); expected a directory path";
  // The directory itself, else the nearest parent that exists (the run creates the rest).
  fs::path path = requested;
  while (!fs::exists(fs::symlink_status(path, ec)) && path.has_parent_path() && path.parent_path() != path)
    path = path.parent_path();
  const std::string what = path == requested ? "" : " (its parent '" + path.string() + "')";
  if (!fs::is_directory(path, ec))
    return "-output_dir '" + dir_name + "'" + what + " is not a directory; expected a writable directory";
  if (access(path.c_str(), W_OK | X_OK) != 0)
    return "-output_dir '" + dir_name + "'" + what + " is not writable; expected a writable directory";
  return "";
}

std::string PrepareOutputDirectory(const std::string &dir_name, int &made) {
  const fs::path dir(dir_name);
  std::error_code ec;
  // DIR and the parents of it that do not exist yet: the directories this run makes.
  made = 0;
  fs::path p = fs::absolute(dir, ec).lexically_normal();
  if (p.filename().empty()) p = p.parent_path(); // "DIR/"
  std::error_code missing; // symlink_status reports a missing path through it too
  for (; !ec && p.has_relative_path() && !fs::exists(fs::symlink_status(p, missing)); p = p.parent_path()) ++made;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    return "-output_dir '" + dir_name + "' cannot be created (" + ec.message() + "); expected a writable directory";
  const fs::path current = CurrentRun(dir);
  for (const auto &entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    const bool stale_run = name.rfind(RUN_PREFIX, 0) == 0 && entry.path().filename() != current;
    const bool stale_link = name.size() > 4 && name.compare(name.size() - 4, 4, ".new") == 0 && entry.is_symlink();
    std::error_code ignored;
    if (stale_run || stale_link) fs::remove_all(entry.path(), ignored);
  }
  const fs::path staging = dir / STAGING;
  fs::remove_all(staging, ec);
  fs::create_directory(staging, ec);
  const fs::path probe = staging / ".probe";
  std::ofstream f(probe);
  const bool ok = !ec && f;
  f.close();
  fs::remove(probe, ec);
  return ok ? "" : "-output_dir '" + dir_name + "' is not writable; expected a writable directory";
}

std::string PublishOutputDirectory(const std::string &dir_name) {
  const fs::path dir(dir_name);
  const fs::path previous = CurrentRun(dir);
  const auto stamp = std::chrono::system_clock::now().time_since_epoch().count();
  const fs::path run = std::string(RUN_PREFIX) + std::to_string(stamp) + "_" + std::to_string(getpid());
  std::error_code ec;
  fs::rename(dir / STAGING, dir / run, ec);
  if (ec) return "cannot rename '" + (dir / STAGING).string() + "' to '" + (dir / run).string() + "': " + ec.message();
  // The switch: every file of DIR changes with this one rename.
  std::string error = ReplaceLink(dir / CURRENT, run);
  if (!error.empty()) return error;
  // The links DIR/NAME -> current/NAME never change once made. A regular file left by an earlier layout is
  // replaced, summary.json first and last, so that a reader never finds it beside files of another run.
  if (!fs::is_symlink(dir / "summary.json")) fs::remove(dir / "summary.json", ec);
  for (const char *name : OUTPUT_FILES) {
    // A file this run did not write (no obstacle, no contact boundary) loses its link, which would dangle now.
    if (!fs::exists(dir / run / name)) {
      if (fs::is_symlink(dir / name)) fs::remove(dir / name, ec);
      continue;
    }
    if (fs::is_symlink(dir / name) && fs::read_symlink(dir / name, ec) == fs::path(CURRENT) / name) continue;
    error = ReplaceLink(dir / name, fs::path(CURRENT) / name);
    if (!error.empty()) return error;
  }
  if (!previous.empty() && previous != run) fs::remove_all(dir / previous, ec);
  return "";
}

} // namespace signorini
