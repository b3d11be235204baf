// The layout of an output directory and its all-or-nothing switch: a run writes into DIR/incomplete/, which becomes
// DIR/run_<id>/ when it succeeds; DIR/current is a symbolic link to the published run and one rename of that link
// replaces every file at once. DIR/solution.h5, solution.xdmf, the per-block XDMF files, nodes.csv and summary.json
// link to current/.
// Plain file-system code, called on one rank.
#pragma once

#include <string>

namespace signorini {

/// The files a run publishes, in the order a reader should trust them (summary.json says the rest is complete).
/// obstacle.xdmf and contact_boundary.xdmf are written only when there is an obstacle grid, a contact boundary.
inline constexpr const char *OUTPUT_FILES[] = {"solution.h5",           "solution.xdmf", "body.xdmf", "obstacle.xdmf",
                                               "contact_boundary.xdmf", "nodes.csv",     "summary.json"};

/// DIR/incomplete/, where a run writes its files.
std::string StagingDirectory(const std::string &dir);

/// Why DIR could not become an output directory, found without touching anything: DIR, or the nearest of its parents
/// that exists, is not a directory or not writable. Empty when it looks fine (PrepareOutputDirectory has the last
/// word). Lets the options report a bad -output_dir before the mesh is read.
std::string OutputDirectoryProblem(const std::string &dir);

/// Makes DIR (and the parents it lacks), removes what an interrupted run or switch left beside the published run
/// (stale run_* directories, a temporary link), and recreates an empty DIR/incomplete/. Returns an empty string on
/// success, else the reason. made: how many directories it made, DIR and its parents (0 when DIR existed), which a
/// failed run removes again when they are left empty (RemoveOnFailure).
std::string PrepareOutputDirectory(const std::string &dir, int &made);

/// Publishes DIR/incomplete/ (complete, summary.json included) as the current run of DIR: renames it to a fresh
/// DIR/run_<id>/, points DIR/current at it with one rename of a new link over the old one, then removes the earlier
/// run. A kill at any point leaves either the earlier run or this one, whole. Returns "" or the reason of a failure.
std::string PublishOutputDirectory(const std::string &dir);

} // namespace signorini
