// Meshing a gmsh .geo file in a child process, so that a gmsh crash or a mesh too large for memory is an input error.
#include "signorini/mesh/geo_mesher.hpp"

#include <gmsh.h>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <sstream>
#include <vector>

namespace signorini {

namespace {

/// Peak resident memory per cell of a whole run with the default solver on one rank (docs/performance.md: 6.6 GB at
/// 2.06M displacement dofs, 2.05M triangles of the Hertz mesh).
constexpr double BYTES_PER_CELL = 3.2e3;

std::string Format(double x) {
  std::ostringstream s;
  s.precision(3);
  s << x;
  return s.str();
}

/// The child's work: mesh geo into msh. Writes "algorithm N\n" before meshing the surfaces, then "error ...\n" on
/// failure, into the pipe fd. Returns the exit status.
int MeshInChild(const std::string &geo, const GeoMeshing &meshing, const std::string &msh, int fd) {
  auto say = [fd](const std::string &line) {
    const std::string text = line + "\n";
    return write(fd, text.data(), text.size()) == (ssize_t)text.size();
  };
  try {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("Mesh.MeshSizeFactor", meshing.size_factor);
    gmsh::open(geo);
    gmsh::model::mesh::generate(1);
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> tags, nodes;
    gmsh::model::mesh::getElements(types, tags, nodes, 1, -1);
    double length = 0, n = 0;
    for (std::size_t k = 0; k < types.size(); ++k)
      for (std::size_t e = 0; e + 1 < nodes[k].size(); e += 2) {
        std::vector<double> a, b, p;
        gmsh::model::mesh::getNode(nodes[k][e], a, p);
        gmsh::model::mesh::getNode(nodes[k][e + 1], b, p);
        length += std::hypot(b[0] - a[0], b[1] - a[1]);
        n += 1;
      }
    double x0, y0, z0, x1, y1, z1;
    gmsh::model::getBoundingBox(-1, -1, x0, y0, z0, x1, y1, z1);
    const double estimate = EstimateCells((x1 - x0) * (y1 - y0), length, n);
    if (meshing.max_cells > 0 && estimate > meshing.max_cells) {
      say("error mesh file '" + geo + "' would have about " + Format(estimate) + " cells (bounding box " +
          Format(x1 - x0) + " x " + Format(y1 - y0) + ", mean boundary size " + Format(length / n) +
          "), more than -mesh_max_cells " + Format(meshing.max_cells) +
          "; expected a coarser mesh (a larger -mesh_size_factor or characteristic length) or a larger -mesh_max_cells");
      return 2;
    }
    double algorithm = 0;
    gmsh::option::getNumber("Mesh.Algorithm", algorithm);
    say("algorithm " + Format(algorithm));
    // Mesh up to the highest dimension of the geometry (3 when it has volumes).
    std::vector<std::pair<int, int>> volumes;
    gmsh::model::getEntities(volumes, 3);
    gmsh::model::mesh::generate(volumes.empty() ? 2 : 3);
    gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
    gmsh::option::setNumber("Mesh.Binary", 1);
    gmsh::option::setNumber("Mesh.SaveAll", 1);
    gmsh::write(msh);
    gmsh::finalize();
    return 0;
  } catch (const std::exception &e) {
    say("error cannot read mesh file '" + geo + "': " + LastGmshError(e.what()) +
        "; expected a valid gmsh .msh or .geo file");
  } catch (...) {
    say("error cannot read mesh file '" + geo + "': " + LastGmshError("gmsh failed") +
        "; expected a valid gmsh .msh or .geo file");
  }
  return 1;
}

} // namespace

std::string LastGmshError(const std::string &fallback) {
  std::string err;
  try {
    gmsh::logger::getLastError(err);
  } catch (...) {
  }
  return err.empty() ? fallback : err;
}

double EstimateCells(double area, double length, double n) {
  if (n <= 0 || length <= 0) return 0;
  const double h = length / n;
  return 4 * area / (std::sqrt(3.0) * h * h);
}

double DefaultMaxCells() {
  const double pages = (double)sysconf(_SC_PHYS_PAGES), page = (double)sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? std::floor(pages * page / BYTES_PER_CELL) : 2e7;
}

std::string MeshGeo(const std::string &geo, const GeoMeshing &meshing, std::string &msh) {
  const char *tmpdir = std::getenv("TMPDIR");
  std::string pattern = std::string(tmpdir && *tmpdir ? tmpdir : "/tmp") + "/signorini_XXXXXX.msh";
  const int tmp = mkstemps(pattern.data(), 4);
  if (tmp < 0) return "cannot create a temporary file for meshing '" + geo + "' (" + std::strerror(errno) + ")";
  close(tmp);
  msh = pattern;
  int fds[2];
  if (pipe(fds) != 0) return "cannot mesh '" + geo + "': pipe failed (" + std::strerror(errno) + ")";
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid < 0) return "cannot mesh '" + geo + "': fork failed (" + std::strerror(errno) + ")";
  if (pid == 0) {
    close(fds[0]);
    // PETSc's handlers would report a gmsh crash as PETSc's own; an interrupt of the run reaches the child through
    // the process group and needs no handler either.
    for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGINT, SIGTERM}) std::signal(sig, SIG_DFL);
    _exit(MeshInChild(geo, meshing, msh, fds[1]));
  }
  close(fds[1]);
  std::string report;
  char buffer[4096];
  for (ssize_t got; (got = read(fds[0], buffer, sizeof(buffer))) != 0;) {
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) break;
    report.append(buffer, got);
  }
  close(fds[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  std::string algorithm, error;
  std::istringstream lines(report);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("algorithm ", 0) == 0) algorithm = line.substr(10);
    if (line.rfind("error ", 0) == 0) error = line.substr(6);
  }
  if (WIFSIGNALED(status)) {
    error = "gmsh crashed (signal " + std::to_string(WTERMSIG(status)) + ") while " +
            (algorithm.empty() ? "reading '" + geo + "'" : "meshing the surfaces of '" + geo + "'") +
            (algorithm.empty() ? "; expected a .geo file that gmsh reads"
                               : " with Mesh.Algorithm = " + algorithm + "; expected a .geo that gmsh meshes: set " +
                                     "another Mesh.Algorithm in it (1 MeshAdapt, 5 Delaunay, 6 Frontal-Delaunay)");
  } else if (error.empty() && (!WIFEXITED(status) || WEXITSTATUS(status) != 0)) {
    error = "gmsh stopped (exit status " + std::to_string(WEXITSTATUS(status)) + ") while meshing '" + geo +
            "'; expected a .geo file that gmsh meshes";
  }
  if (!error.empty()) std::remove(msh.c_str()), msh.clear();
  return error;
}

} // namespace signorini
