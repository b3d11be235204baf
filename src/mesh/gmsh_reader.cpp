// Reading gmsh files (and .geo files, meshed in a child process) on one rank through the gmsh API.
#include "signorini/mesh/serial_mesh.hpp"

#include "signorini/mesh/geo_mesher.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <map>
#include <sstream>
#include <unordered_map>

namespace signorini {

namespace {

bool EndsWith(const std::string &s, const std::string &suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// Gmsh element types signorini reads: 1 line (2 nodes), 2 triangle (3), 3 quadrangle (4), 15 point.
constexpr int GMSH_LINE = 1, GMSH_TRIANGLE = 2, GMSH_QUADRANGLE = 3;

std::string ReadModel(const std::string &path, SerialMesh &mesh) {
  std::vector<std::pair<int, int>> entities3;
  gmsh::model::getEntities(entities3, 3);
  std::vector<int> types3;
  std::vector<std::vector<std::size_t>> tags3, nodes3;
  gmsh::model::mesh::getElements(types3, tags3, nodes3, 3, -1);
  std::size_t n3 = 0;
  for (auto &t : tags3) n3 += t.size();
  if (n3 > 0) return "mesh '" + path + "' has 3D elements; this version of signorini solves 2D problems only";

  std::vector<int> types;
  std::vector<std::vector<std::size_t>> elem_tags, elem_nodes;
  gmsh::model::mesh::getElements(types, elem_tags, elem_nodes, 2, -1);
  std::size_t ncells = 0;
  for (std::size_t k = 0; k < types.size(); ++k) {
    if (types[k] != GMSH_TRIANGLE && types[k] != GMSH_QUADRANGLE) {
      std::string name;
      int d, order, nn, npr;
      std::vector<double> lc;
      gmsh::model::mesh::getElementProperties(types[k], name, d, order, nn, lc, npr);
      return "mesh '" + path + "' has elements of type '" + name +
             "'; expected linear triangles (3 nodes) and quadrilaterals (4 nodes)";
    }
    ncells += elem_tags[k].size();
  }
  if (ncells == 0)
    return "mesh '" + path + "' has no triangles or quadrilaterals (a 1D-only or empty mesh?); expected a 2D mesh";

  std::vector<std::size_t> all_tags;
  std::vector<double> all_coords, params;
  gmsh::model::mesh::getNodes(all_tags, all_coords, params, -1, -1, false, false);
  std::unordered_map<std::size_t, std::size_t> tag_pos;
  tag_pos.reserve(all_tags.size());
  for (std::size_t i = 0; i < all_tags.size(); ++i) {
    if (!tag_pos.emplace(all_tags[i], i).second)
      return "mesh '" + path + "' has duplicate node tag " + std::to_string(all_tags[i]) + "; expected unique node tags";
  }

  // Nodes used by cells, numbered in the order they appear in the file.
  std::vector<int> used(all_tags.size(), -1);
  for (auto &nodes : elem_nodes)
    for (std::size_t t : nodes) {
      auto it = tag_pos.find(t);
      if (it == tag_pos.end()) return "mesh '" + path + "' has an element referring to unknown node " + std::to_string(t);
      used[it->second] = 0;
    }
  for (std::size_t i = 0; i < all_tags.size(); ++i)
    if (used[i] == 0) {
      used[i] = mesh.NumNodes();
      mesh.node_tags.push_back(all_tags[i]);
      mesh.coords.push_back(all_coords[3 * i]);
      mesh.coords.push_back(all_coords[3 * i + 1]);
      if (std::abs(all_coords[3 * i + 2]) > 0) {
        // Planar meshes away from z = 0 are fine; a curved surface is not: checked after reading all nodes.
      }
    }
  double zmin = 1e300, zmax = -1e300;
  for (std::size_t i = 0; i < all_tags.size(); ++i)
    if (used[i] >= 0) zmin = std::min(zmin, all_coords[3 * i + 2]), zmax = std::max(zmax, all_coords[3 * i + 2]);
  if (zmax - zmin > 1e-12 * (1.0 + std::abs(zmax)))
    return "mesh '" + path + "' is not planar (z varies); expected a 2D mesh in the x-y plane";

  auto node_index = [&](std::size_t tag) { return used[tag_pos.at(tag)]; };
  std::unordered_map<std::size_t, int> cell_of_tag;
  for (std::size_t k = 0; k < types.size(); ++k) {
    const int nv = types[k] == GMSH_TRIANGLE ? 3 : 4;
    for (std::size_t e = 0; e < elem_tags[k].size(); ++e) {
      for (int j = 0; j < nv; ++j) mesh.cell_nodes.push_back(node_index(elem_nodes[k][nv * e + j]));
      mesh.cell_offsets.push_back((int)mesh.cell_nodes.size());
      if (!cell_of_tag.emplace(elem_tags[k][e], mesh.NumCells()).second)
        return "mesh '" + path + "' has duplicate element tag " + std::to_string(elem_tags[k][e]);
      mesh.cell_tags.push_back(elem_tags[k][e]);
    }
  }

  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, -1);
  for (auto [dim, tag] : groups) {
    if (dim > 2) continue;
    PhysicalGroup g;
    g.dim = dim;
    g.tag = tag;
    gmsh::model::getPhysicalName(dim, tag, g.name);
    if (g.name.empty()) g.name = std::to_string(tag);
    std::vector<int> ents;
    gmsh::model::getEntitiesForPhysicalGroup(dim, tag, ents);
    for (int ent : ents) {
      std::vector<int> et;
      std::vector<std::vector<std::size_t>> etags, enodes;
      gmsh::model::mesh::getElements(et, etags, enodes, dim, ent);
      for (std::size_t k = 0; k < et.size(); ++k) {
        if (dim == 1) {
          if (et[k] != GMSH_LINE)
            return "physical curve '" + g.name + "' has non-linear line elements; expected 2-node lines";
          for (std::size_t t : enodes[k]) {
            auto it = tag_pos.find(t);
            if (it == tag_pos.end() || used[it->second] < 0)
              return "physical curve '" + g.name + "' has a node that belongs to no cell";
            g.edges.push_back(used[it->second]);
          }
        } else if (dim == 2) {
          for (std::size_t t : etags[k]) g.cells.push_back(cell_of_tag.at(t));
        }
        // The nodes of the group's elements: a format 2.2 file classifies each node on one entity only, so the
        // entity's own nodes (below) miss those it shares with neighbouring entities (corners, curve ends).
        for (std::size_t t : enodes[k]) {
          auto it = tag_pos.find(t);
          if (it != tag_pos.end() && used[it->second] >= 0) g.nodes.push_back(used[it->second]);
        }
      }
      std::vector<std::size_t> ntags;
      std::vector<double> nc, np;
      gmsh::model::mesh::getNodes(ntags, nc, np, dim, ent, true, false);
      for (std::size_t t : ntags) {
        auto it = tag_pos.find(t);
        if (it == tag_pos.end() || used[it->second] < 0) {
          if (dim == 0) return "physical point '" + g.name + "' is a node that belongs to no cell";
          continue;
        }
        g.nodes.push_back(used[it->second]);
      }
    }
    std::sort(g.nodes.begin(), g.nodes.end());
    g.nodes.erase(std::unique(g.nodes.begin(), g.nodes.end()), g.nodes.end());
    if (g.nodes.empty() && g.cells.empty()) continue;
    mesh.groups.push_back(std::move(g));
  }
  return "";
}

} // namespace

std::string ReadGmsh(const std::string &path, double size_factor, SerialMesh &mesh, double max_cells) {
  mesh = SerialMesh{};
  FILE *f = std::fopen(path.c_str(), "rb");
  if (!f) return "cannot open mesh file '" + path + "'; expected a readable gmsh .msh or .geo file";
  char head[16] = {0};
  const std::size_t nread = std::fread(head, 1, sizeof(head) - 1, f);
  const bool unreadable = std::ferror(f) != 0; // a directory opens but does not read
  std::fclose(f);
  const bool geo = EndsWith(path, ".geo");
  if (unreadable) return "cannot read mesh file '" + path + "' (a directory?); expected a gmsh .msh or .geo file";
  if (nread == 0) return "mesh file '" + path + "' is empty; expected a gmsh .msh or .geo file";
  if (!geo && std::string(head).rfind("$MeshFormat", 0) != 0)
    return "mesh file '" + path + "' is not a gmsh mesh (no $MeshFormat header); expected a gmsh .msh file";

  // A .geo is meshed by gmsh in a child process into a temporary .msh, read below like any other.
  std::string source = path;
  if (geo) {
    const std::string error = MeshGeo(path, {size_factor, max_cells}, source);
    if (!error.empty()) return error;
  }
  std::string error;
  try {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    // Warnings reach the logger (not the terminal): the .msh 2 reader only warns about a duplicate node tag and
    // keeps one of the nodes.
    gmsh::option::setNumber("General.Verbosity", 2);
    gmsh::logger::start();
    gmsh::open(source);
    std::vector<std::string> log;
    gmsh::logger::get(log);
    gmsh::logger::stop();
    const std::string duplicate = "Skipping duplicate node ";
    for (const auto &line : log)
      if (error.empty() && line.find(duplicate) != std::string::npos)
        error = "mesh '" + path + "' has duplicate node tag " + line.substr(line.find(duplicate) + duplicate.size()) +
                "; expected unique node tags";
    if (error.empty()) error = ReadModel(path, mesh);
  } catch (const std::exception &e) {
    error = "cannot read mesh file '" + path + "': " + LastGmshError(e.what()) +
            "; expected a valid gmsh .msh or .geo file";
  } catch (...) {
    error = "cannot read mesh file '" + path + "': " + LastGmshError("gmsh failed") +
            "; expected a valid gmsh .msh or .geo file";
  }
  try {
    gmsh::finalize();
  } catch (...) {
  }
  if (geo) std::remove(source.c_str());
  if (error.empty()) {
    error = CheckAndOrientCells(mesh);
    if (!error.empty()) error = "mesh '" + path + "': " + error;
  }
  return error;
}

std::string CheckAndOrientCells(SerialMesh &mesh) {
  const int nc = mesh.NumCells();
  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
  for (int i = 0; i < mesh.NumNodes(); ++i) {
    xmin = std::min(xmin, mesh.coords[2 * i]), xmax = std::max(xmax, mesh.coords[2 * i]);
    ymin = std::min(ymin, mesh.coords[2 * i + 1]), ymax = std::max(ymax, mesh.coords[2 * i + 1]);
  }
  const double area_tol = 1e-14 * ((xmax - xmin) * (xmax - xmin) + (ymax - ymin) * (ymax - ymin));
  std::vector<int> sign(nc, 0);
  int npos = 0, nneg = 0;
  for (int c = 0; c < nc; ++c) {
    const int n = mesh.CellSize(c);
    const int *v = &mesh.cell_nodes[mesh.cell_offsets[c]];
    int pos = 0, neg = 0;
    for (int k = 0; k < n; ++k) {
      // Twice the area of the corner triangle at vertex k: positive for a counter-clockwise corner.
      const double *a = &mesh.coords[2 * v[(k + n - 1) % n]], *b = &mesh.coords[2 * v[k]],
                   *d = &mesh.coords[2 * v[(k + 1) % n]];
      const double cross = (b[0] - a[0]) * (d[1] - b[1]) - (b[1] - a[1]) * (d[0] - b[0]);
      if (cross > area_tol) ++pos;
      else if (cross < -area_tol) ++neg;
    }
    if (pos + neg < n && (pos == 0 || neg == 0))
      return "element " + std::to_string(mesh.cell_tags[c]) + " has zero area (or a degenerate corner); expected " +
             "a valid mesh";
    if (pos && neg)
      return "element " + std::to_string(mesh.cell_tags[c]) + " is not convex (self-intersecting or inverted " +
             "quadrilateral); expected convex elements";
    sign[c] = pos ? 1 : -1;
    (pos ? npos : nneg)++;
  }
  if (npos && nneg) {
    const int minority = npos >= nneg ? -1 : 1;
    int first = 0;
    while (sign[first] != minority) ++first;
    std::ostringstream s;
    s << std::min(npos, nneg) << " inverted element(s) of " << nc << " (e.g. element "
      << mesh.cell_tags[first] << "); expected all elements oriented alike";
    return s.str();
  }
  if (nneg) {
    for (int c = 0; c < nc; ++c) std::reverse(&mesh.cell_nodes[mesh.cell_offsets[c]], &mesh.cell_nodes[mesh.cell_offsets[c + 1]]);
  }
  return "";
}

} // namespace signorini
