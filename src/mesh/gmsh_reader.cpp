// Reading gmsh files (and .geo files, meshed in a child process) on one rank through the gmsh API.
#include "signorini/mesh/serial_mesh.hpp"

#include "signorini/core/parse.hpp"
#include "signorini/mesh/geo_mesher.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <functional>
#include <map>
#include <sstream>
#include <unordered_map>

namespace signorini {

namespace {

/// Gmsh element types signorini reads: 1 line (2 nodes), 2 triangle (3), 3 quadrangle (4), 4 tetrahedron (4),
/// 5 hexahedron (8), 7 pyramid (5; gmsh puts them between tetrahedra and the quadrilateral faces of hexahedra).
constexpr int GMSH_LINE = 1, GMSH_TRIANGLE = 2, GMSH_QUADRANGLE = 3, GMSH_TETRAHEDRON = 4, GMSH_HEXAHEDRON = 5,
              GMSH_PYRAMID = 7;

/// Number of vertices of a cell type signorini reads in dimension dim, 0 for any other type.
int CellVertices(int dim, int type) {
  if (dim == 2) return type == GMSH_TRIANGLE ? 3 : type == GMSH_QUADRANGLE ? 4 : 0;
  return type == GMSH_TETRAHEDRON ? 4 : type == GMSH_PYRAMID ? 5 : type == GMSH_HEXAHEDRON ? 8 : 0;
}

/// Positions of unique tags (gmsh's node or element tags): a table indexed by tag when the tags are compact (gmsh
/// numbers from 1 without gaps), a hash map otherwise (hash look-ups would dominate the reading of a large mesh).
class TagIndex {
public:
  /// Indexes tags[i] -> i; returns false and sets duplicate when a tag occurs twice.
  bool Build(const std::vector<std::size_t> &tags, std::size_t &duplicate) {
    std::size_t max_tag = 0;
    for (std::size_t t : tags) max_tag = std::max(max_tag, t);
    dense_ = max_tag <= 4 * tags.size() + 1024;
    if (dense_) table_.assign(max_tag + 1, NONE);
    else map_.reserve(tags.size());
    for (std::size_t i = 0; i < tags.size(); ++i) {
      const bool fresh = dense_ ? table_[tags[i]] == NONE : map_.emplace(tags[i], i).second;
      if (!fresh) {
        duplicate = tags[i];
        return false;
      }
      if (dense_) table_[tags[i]] = i;
    }
    return true;
  }
  /// The position of tag, or NONE.
  std::size_t Find(std::size_t tag) const {
    if (dense_) return tag < table_.size() ? table_[tag] : NONE;
    const auto it = map_.find(tag);
    return it == map_.end() ? NONE : it->second;
  }
  static constexpr std::size_t NONE = ~std::size_t(0);

private:
  bool dense_ = true;
  std::vector<std::size_t> table_;
  std::unordered_map<std::size_t, std::size_t> map_;
};

/// Element blocks of a gmsh model (types, and per type the element tags and their nodes), as getElements gives them.
struct ElementBlocks {
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> tags, nodes;
};

/// The nodes used by cells, numbered in the order they appear in the file: a node tag's position among the file's
/// nodes (positions), and the number of the node at each position (used; -1: no cell uses it).
struct NodeNumbering {
  TagIndex positions;
  std::vector<int> used;
  /// The number of a node tag among the nodes used by cells, -1 for an unknown tag or an unused node.
  int Find(std::size_t tag) const {
    const std::size_t pos = positions.Find(tag);
    return pos == TagIndex::NONE ? -1 : used[pos];
  }
};

/// The cells of the model: the elements of its highest dimension (3 when it has any volume element, which sets
/// mesh.dim), of the types signorini reads. Returns the first error, or "".
std::string ReadCellBlocks(const std::string &path, SerialMesh &mesh, ElementBlocks &cells) {
  gmsh::model::mesh::getElements(cells.types, cells.tags, cells.nodes, 3, -1);
  std::size_t n3 = 0;
  for (auto &t : cells.tags)
    n3 += t.size();
  mesh.dim = n3 > 0 ? 3 : 2;
  const int dim = mesh.dim;
  if (dim == 2) gmsh::model::mesh::getElements(cells.types, cells.tags, cells.nodes, 2, -1);
  const char *expected = dim == 2 ? "linear triangles (3 nodes) and quadrilaterals (4 nodes)"
                                  : "linear tetrahedra (4 nodes), pyramids (5 nodes) and hexahedra (8 nodes)";
  std::size_t ncells = 0;
  for (std::size_t k = 0; k < cells.types.size(); ++k) {
    if (CellVertices(dim, cells.types[k]) == 0) {
      std::string name;
      int d, order, nn, npr;
      std::vector<double> lc;
      gmsh::model::mesh::getElementProperties(cells.types[k], name, d, order, nn, lc, npr);
      return "mesh '" + path + "' has elements of type '" + name + "'; expected " + expected;
    }
    ncells += cells.tags[k].size();
  }
  if (ncells == 0)
    return "mesh '" + path + "' has no triangles or quadrilaterals (a 1D-only or empty mesh?); expected a 2D or 3D "
           "mesh";
  return "";
}

/// Numbers the nodes that cells use in the order they appear in the file (nodes) and appends their tags and
/// coordinates to mesh; a 2D mesh must lie in a plane z = const. Returns the first error, or "".
std::string NumberNodes(const std::string &path, const ElementBlocks &cells, SerialMesh &mesh, NodeNumbering &nodes) {
  const int dim = mesh.dim;
  std::vector<std::size_t> all_tags;
  std::vector<double> all_coords, params;
  gmsh::model::mesh::getNodes(all_tags, all_coords, params, -1, -1, false, false);
  std::size_t duplicate = 0;
  if (!nodes.positions.Build(all_tags, duplicate))
    return "mesh '" + path + "' has duplicate node tag " + std::to_string(duplicate) + "; expected unique node tags";
  std::vector<int> &used = nodes.used;
  used.assign(all_tags.size(), -1);
  for (auto &cell_nodes : cells.nodes)
    for (std::size_t t : cell_nodes) {
      const std::size_t pos = nodes.positions.Find(t);
      if (pos == TagIndex::NONE)
        return "mesh '" + path + "' has an element referring to unknown node " + std::to_string(t);
      used[pos] = 0;
    }
  for (std::size_t i = 0; i < all_tags.size(); ++i)
    if (used[i] == 0) {
      used[i] = mesh.NumNodes();
      mesh.node_tags.push_back(all_tags[i]);
      for (int d = 0; d < dim; ++d) mesh.coords.push_back(all_coords[3 * i + d]);
    }
  // A 2D mesh may lie in any plane z = const (a curved surface is not a 2D mesh).
  double zmin = 1e300, zmax = -1e300;
  for (std::size_t i = 0; i < all_tags.size(); ++i)
    if (used[i] >= 0) zmin = std::min(zmin, all_coords[3 * i + 2]), zmax = std::max(zmax, all_coords[3 * i + 2]);
  if (dim == 2 && zmax - zmin > 1e-12 * (1.0 + std::abs(zmax)))
    return "mesh '" + path + "' has no volume cells and is not planar (z varies): a surface mesh cannot be the body; "
           "expected tetrahedra, pyramids or hexahedra (3D) or a 2D mesh in the x-y plane";
  return "";
}

/// Appends the cells to mesh (their nodes by number, offsets and tags) and indexes their tags (cell_of_tag). Returns
/// the first error, or "".
std::string AddCells(const std::string &path, const ElementBlocks &cells, const NodeNumbering &nodes, SerialMesh &mesh,
                     TagIndex &cell_of_tag) {
  for (std::size_t k = 0; k < cells.types.size(); ++k) {
    const int nv = CellVertices(mesh.dim, cells.types[k]);
    for (std::size_t e = 0; e < cells.tags[k].size(); ++e) {
      for (int j = 0; j < nv; ++j)
        mesh.cell_nodes.push_back(nodes.Find(cells.nodes[k][nv * e + j]));
      mesh.cell_offsets.push_back((int)mesh.cell_nodes.size());
      mesh.cell_tags.push_back(cells.tags[k][e]);
    }
  }
  std::size_t duplicate = 0;
  if (!cell_of_tag.Build(mesh.cell_tags, duplicate))
    return "mesh '" + path + "' has duplicate element tag " + std::to_string(duplicate);
  return "";
}

/// Elements of one type of a physical group g of dimension dim below the mesh's: a curve's lines (edges), a
/// surface's faces (face_nodes) of a 3D mesh. Returns the first error, or "".
std::string AddGroupFacets(const NodeNumbering &nodes, int dim, int type, const std::vector<std::size_t> &tags,
                           const std::vector<std::size_t> &element_nodes, PhysicalGroup &g) {
  if (dim == 1) {
    if (type != GMSH_LINE) return "physical curve '" + g.name + "' has non-linear line elements; expected 2-node lines";
    for (std::size_t t : element_nodes) {
      const int v = nodes.Find(t);
      if (v < 0) return "physical curve '" + g.name + "' has a node that belongs to no cell";
      g.edges.push_back(v);
    }
  } else if (dim == 2) {
    // A physical surface of a 3D mesh: its triangles and quadrilaterals are boundary faces (checked when the DMPlex
    // is labelled).
    const int nv = type == GMSH_TRIANGLE ? 3 : type == GMSH_QUADRANGLE ? 4 : 0;
    if (nv == 0)
      return "physical surface '" + g.name +
             "' has non-linear surface elements; expected 3-node triangles and "
             "4-node quadrilaterals";
    for (std::size_t e = 0; e < tags.size(); ++e) {
      for (int j = 0; j < nv; ++j) {
        const int v = nodes.Find(element_nodes[nv * e + j]);
        if (v < 0) return "physical surface '" + g.name + "' has a node that belongs to no cell";
        g.face_nodes.push_back(v);
      }
      g.face_offsets.push_back((int)g.face_nodes.size());
    }
  }
  return "";
}

/// Entity ent of physical group g of dimension dim: its cells (a group of the mesh's dimension), or its facets and
/// nodes. Returns the first error, or "".
std::string AddGroupEntity(const SerialMesh &mesh, const NodeNumbering &nodes, const TagIndex &cell_of_tag, int dim,
                           int ent, PhysicalGroup &g) {
  std::vector<int> et;
  std::vector<std::vector<std::size_t>> etags, enodes;
  gmsh::model::mesh::getElements(et, etags, enodes, dim, ent);
  for (std::size_t k = 0; k < et.size(); ++k) {
    if (dim == mesh.dim) {
      for (std::size_t t : etags[k])
        g.cells.push_back((int)cell_of_tag.Find(t));
    } else if (dim == 1 || dim == 2) {
      if (std::string error = AddGroupFacets(nodes, dim, et[k], etags[k], enodes[k], g); !error.empty()) return error;
    }
    // The nodes of the group's elements: a format 2.2 file classifies each node on one entity only, so the entity's
    // own nodes (below) miss those it shares with neighbouring entities (corners, curve ends). A group of cells has
    // its nodes through its cells.
    if (dim < mesh.dim)
      for (std::size_t t : enodes[k])
        if (nodes.Find(t) >= 0) g.nodes.push_back(nodes.Find(t));
  }
  if (dim == mesh.dim) return "";
  std::vector<std::size_t> ntags;
  std::vector<double> nc, np;
  gmsh::model::mesh::getNodes(ntags, nc, np, dim, ent, true, false);
  for (std::size_t t : ntags) {
    const int v = nodes.Find(t);
    if (v < 0) {
      if (dim == 0) return "physical point '" + g.name + "' is a node that belongs to no cell";
      continue;
    }
    g.nodes.push_back(v);
  }
  return "";
}

/// Physical group (dim, tag): its name (the tag when it has none), cells, facets and sorted nodes. Returns the first
/// error, or "".
std::string ReadPhysicalGroup(const SerialMesh &mesh, const NodeNumbering &nodes, const TagIndex &cell_of_tag, int dim,
                              int tag, PhysicalGroup &g) {
  g.dim = dim;
  g.tag = tag;
  gmsh::model::getPhysicalName(dim, tag, g.name);
  if (g.name.empty()) g.name = std::to_string(tag);
  std::vector<int> ents;
  gmsh::model::getEntitiesForPhysicalGroup(dim, tag, ents);
  for (int ent : ents)
    if (std::string error = AddGroupEntity(mesh, nodes, cell_of_tag, dim, ent, g); !error.empty()) return error;
  std::sort(g.nodes.begin(), g.nodes.end());
  g.nodes.erase(std::unique(g.nodes.begin(), g.nodes.end()), g.nodes.end());
  return "";
}

/// The loaded gmsh model as a serial mesh: its cells, the nodes they use and its physical groups (those with nodes or
/// cells). Returns the first error, or "".
std::string ReadModel(const std::string &path, SerialMesh &mesh) {
  ElementBlocks cells;
  if (std::string error = ReadCellBlocks(path, mesh, cells); !error.empty()) return error;
  NodeNumbering nodes;
  if (std::string error = NumberNodes(path, cells, mesh, nodes); !error.empty()) return error;
  TagIndex cell_of_tag;
  if (std::string error = AddCells(path, cells, nodes, mesh, cell_of_tag); !error.empty()) return error;
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, -1);
  for (auto [dim, tag] : groups) {
    PhysicalGroup g;
    if (std::string error = ReadPhysicalGroup(mesh, nodes, cell_of_tag, dim, tag, g); !error.empty()) return error;
    if (g.nodes.empty() && g.cells.empty()) continue;
    mesh.groups.push_back(std::move(g));
  }
  return "";
}

/// Opens path with gmsh (a .geo meshed first in a child process) and runs read on the loaded model. what names the
/// kind of file in messages ("mesh", "obstacle mesh"). Returns the first error, or "".
std::string WithGmshModel(const std::string &path, const std::string &what, double size_factor, double max_cells,
                          const std::function<std::string()> &read) {
  FILE *f = std::fopen(path.c_str(), "rb");
  if (!f) return "cannot open " + what + " file '" + path + "'; expected a readable gmsh .msh or .geo file";
  char head[16] = {0};
  const std::size_t nread = std::fread(head, 1, sizeof(head) - 1, f);
  const bool unreadable = std::ferror(f) != 0; // a directory opens but does not read
  std::fclose(f);
  const bool geo = EndsWith(path, ".geo");
  if (unreadable)
    return "cannot read " + what + " file '" + path + "' (a directory?); expected a gmsh .msh or .geo file";
  if (nread == 0) return what + " file '" + path + "' is empty; expected a gmsh .msh or .geo file";
  if (!geo && std::string(head).rfind("$MeshFormat", 0) != 0)
    return what + " file '" + path + "' is not a gmsh mesh (no $MeshFormat header); expected a gmsh .msh file";

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
        error = what + " '" + path + "' has duplicate node tag " +
                line.substr(line.find(duplicate) + duplicate.size()) + "; expected unique node tags";
    if (error.empty()) error = read();
  } catch (const std::exception &e) {
    error = "cannot read " + what + " file '" + path + "': " + LastGmshError(e.what()) +
            "; expected a valid gmsh .msh or .geo file";
  } catch (...) {
    error = "cannot read " + what + " file '" + path + "': " + LastGmshError("gmsh failed") +
            "; expected a valid gmsh .msh or .geo file";
  }
  try {
    gmsh::finalize();
  } catch (...) {
  }
  if (geo) std::remove(source.c_str());
  return error;
}

/// What a dimension-dim obstacle mesh must consist of, for messages.
std::string ExpectedElements(int dim) {
  return dim == 1 ? "2-node line elements (the obstacle of a 2D body)"
                  : "3-node triangles or 4-node quadrilaterals (the obstacle of a 3D body)";
}

/// The loaded model's entities of dimension dim: those of the physical group named group, or all when it is empty.
std::string GroupEntities(const std::string &where, int dim, const std::string &group, gmsh::vectorpair &entities) {
  if (group.empty()) {
    gmsh::model::getEntities(entities, dim);
    return "";
  }
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, -1);
  std::vector<std::string> names;
  int other_dim = -1;
  for (auto [d, tag] : groups) {
    std::string name;
    gmsh::model::getPhysicalName(d, tag, name);
    if (name.empty()) name = std::to_string(tag);
    names.push_back("'" + name + "' (" + std::to_string(d) + "D)");
    if (name != group) continue;
    if (d != dim) {
      other_dim = d;
      continue;
    }
    std::vector<int> tags;
    gmsh::model::getEntitiesForPhysicalGroup(d, tag, tags);
    for (int t : tags) entities.emplace_back(d, t);
  }
  if (entities.empty() && other_dim >= 0)
    return where + ": physical group '" + group + "' is " + std::to_string(other_dim) + "D; expected a " +
           std::to_string(dim) + "D group of " + ExpectedElements(dim);
  if (entities.empty())
    return where + " has no physical group '" + group + "'; expected one of: " +
           (names.empty() ? std::string("(the file has no physical groups)") : Join(names, ", "));
  return "";
}

/// The loaded model's elements of dimension dim (of the physical group named group, or all) into set.
std::string ReadElements(const std::string &path, int dim, const std::string &group, ElementSet &set) {
  const std::string where = "obstacle mesh '" + path + "'";
  gmsh::vectorpair entities;
  const std::string error = GroupEntities(where, dim, group, entities);
  if (!error.empty()) return error;
  std::vector<std::size_t> all_tags;
  std::vector<double> all_coords, params;
  gmsh::model::mesh::getNodes(all_tags, all_coords, params, -1, -1, false, false);
  std::unordered_map<std::size_t, std::size_t> tag_pos;
  for (std::size_t i = 0; i < all_tags.size(); ++i) tag_pos.emplace(all_tags[i], i);
  std::unordered_map<std::size_t, int> node_index;
  std::unordered_map<std::size_t, char> seen;
  for (auto [d, ent] : entities) {
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> etags, enodes;
    gmsh::model::mesh::getElements(types, etags, enodes, d, ent);
    for (std::size_t k = 0; k < types.size(); ++k) {
      const int nv = dim == 1 ? (types[k] == GMSH_LINE ? 2 : 0)
                              : (types[k] == GMSH_TRIANGLE ? 3 : types[k] == GMSH_QUADRANGLE ? 4 : 0);
      if (nv == 0 && !etags[k].empty()) {
        std::string name;
        int ed, order, nn, npr;
        std::vector<double> lc;
        gmsh::model::mesh::getElementProperties(types[k], name, ed, order, nn, lc, npr);
        return where + ": element " + std::to_string(etags[k][0]) + " is a '" + name + "'; expected " +
               ExpectedElements(dim);
      }
      for (std::size_t e = 0; e < etags[k].size(); ++e) {
        if (!seen.emplace(etags[k][e], 1).second) continue; // an entity listed twice
        for (int j = 0; j < nv; ++j) {
          const std::size_t t = enodes[k][nv * e + j];
          const auto pos = tag_pos.find(t);
          if (pos == tag_pos.end())
            return where + ": element " + std::to_string(etags[k][e]) + " refers to unknown node " + std::to_string(t);
          const auto [it, added] = node_index.emplace(t, (int)set.node_tags.size());
          if (added) {
            set.node_tags.push_back(t);
            set.coords.insert(set.coords.end(), &all_coords[3 * pos->second], &all_coords[3 * pos->second] + 3);
          }
          set.nodes.push_back(it->second);
        }
        set.offsets.push_back((int)set.nodes.size());
        set.tags.push_back(etags[k][e]);
      }
    }
  }
  if (set.NumElements() == 0) {
    // Say what the file (or group) holds instead: a surface mesh given for a 2D body, a volume mesh without faces.
    std::vector<std::string> held;
    for (int d = 0; d <= 3; ++d) {
      if (d == dim) continue;
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> etags, enodes;
      gmsh::model::mesh::getElements(types, etags, enodes, d, -1);
      std::size_t n = 0;
      for (const auto &t : etags) n += t.size();
      if (n) held.push_back(std::to_string(n) + " element(s) of dimension " + std::to_string(d));
    }
    return where + (group.empty() ? "" : " group '" + group + "'") + " has " +
           (held.empty() ? std::string("no elements") : "only " + Join(held, ", ")) + "; expected " +
           ExpectedElements(dim);
  }
  return "";
}

} // namespace

std::string ReadGmsh(const std::string &path, double size_factor, SerialMesh &mesh, double max_cells) {
  mesh = SerialMesh{};
  std::string error = WithGmshModel(path, "mesh", size_factor, max_cells, [&] { return ReadModel(path, mesh); });
  if (error.empty()) {
    error = CheckAndOrientCells(mesh);
    if (!error.empty()) error = "mesh '" + path + "': " + error;
  }
  return error;
}

std::string ReadGmshElements(const std::string &path, int dim, const std::string &group, ElementSet &set) {
  set = ElementSet{};
  return WithGmshModel(path, "obstacle mesh", 1.0, 0, [&] { return ReadElements(path, dim, group, set); });
}

namespace {

/// Signed measures at the corners of cell c: twice the area of each corner triangle in 2D, the determinant of the
/// three edges leaving each corner in 3D (one for a tetrahedron; the four base corners of a pyramid); positive for a
/// counter-clockwise (2D) or right-handed (3D) cell. Returns the number of measures.
int CornerMeasures(const SerialMesh &mesh, int c, double *m) {
  const int n = mesh.CellSize(c), dim = mesh.dim;
  const int *v = &mesh.cell_nodes[mesh.cell_offsets[c]];
  const auto x = [&](int k) { return &mesh.coords[dim * v[k]]; };
  if (dim == 2) {
    for (int k = 0; k < n; ++k) {
      const double *a = x((k + n - 1) % n), *b = x(k), *d = x((k + 1) % n);
      m[k] = (b[0] - a[0]) * (d[1] - b[1]) - (b[1] - a[1]) * (d[0] - b[0]);
    }
    return n;
  }
  const auto det = [&](int o, int i, int j, int k) {
    double e[3][3];
    for (int d = 0; d < 3; ++d) e[0][d] = x(i)[d] - x(o)[d], e[1][d] = x(j)[d] - x(o)[d], e[2][d] = x(k)[d] - x(o)[d];
    return e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
           e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
  };
  if (n == 4) {
    m[0] = det(0, 1, 2, 3);
    return 1;
  }
  if (n == 5) {
    // Pyramid (gmsh order: base 0-3 counter-clockwise seen from the apex 4): the edges to the next and previous base
    // corner and to the apex. As the collapsed hexahedron of the element (element.cpp), its Jacobian is
    // (1 - z)^2 det(B_xi, B_eta, apex - B) over the base B(xi, eta); at the base corners that is these measures (the
    // apex, where it vanishes, has none).
    for (int k = 0; k < 4; ++k) m[k] = det(k, (k + 1) % 4, (k + 3) % 4, 4);
    return 4;
  }
  // Hexahedron (gmsh order: bottom 0-3 and top 4-7 counter-clockwise seen from above, k + 4 above k): the edges to
  // the next and previous corner of its quadrilateral and to the corner above (below, with the sign turned).
  for (int k = 0; k < 4; ++k) {
    m[k] = det(k, (k + 1) % 4, (k + 3) % 4, k + 4);
    m[k + 4] = -det(k + 4, (k + 1) % 4 + 4, (k + 3) % 4 + 4, k);
  }
  return 8;
}

/// Turns cell c inside out: reverses a polygon; swaps two vertices of a tetrahedron; reverses the base of a pyramid;
/// reverses both quadrilaterals of a hexahedron, keeping each top vertex above its bottom one.
void FlipCell(SerialMesh &mesh, int c) {
  int *v = &mesh.cell_nodes[mesh.cell_offsets[c]];
  if (mesh.dim == 2) std::reverse(v, v + mesh.CellSize(c));
  else if (mesh.CellSize(c) == 4) std::swap(v[1], v[2]);
  else if (mesh.CellSize(c) == 5) std::swap(v[1], v[3]);
  else std::swap(v[1], v[3]), std::swap(v[5], v[7]);
}

} // namespace

std::string CheckAndOrientCells(SerialMesh &mesh) {
  const int nc = mesh.NumCells(), dim = mesh.dim;
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300}, diag2 = 0;
  for (int i = 0; i < mesh.NumNodes(); ++i)
    for (int d = 0; d < dim; ++d)
      lo[d] = std::min(lo[d], mesh.coords[dim * i + d]), hi[d] = std::max(hi[d], mesh.coords[dim * i + d]);
  for (int d = 0; d < dim; ++d) diag2 += (hi[d] - lo[d]) * (hi[d] - lo[d]);
  // A corner measure below 1e-14 of the bounding box's diagonal to the power dim is zero (round-off).
  const double tol = 1e-14 * std::pow(diag2, 0.5 * dim);
  const std::string measure = dim == 2 ? "area" : "volume";
  std::vector<int> sign(nc, 0);
  int npos = 0, nneg = 0;
  for (int c = 0; c < nc; ++c) {
    double m[8];
    const int n = CornerMeasures(mesh, c, m);
    int pos = 0, neg = 0;
    for (int k = 0; k < n; ++k) {
      if (m[k] > tol) ++pos;
      else if (m[k] < -tol) ++neg;
    }
    if (pos + neg < n && (pos == 0 || neg == 0))
      return "element " + std::to_string(mesh.cell_tags[c]) + " has zero " + measure +
             " (or a degenerate corner); expected a valid mesh";
    if (pos && neg)
      return "element " + std::to_string(mesh.cell_tags[c]) + " is not convex (self-intersecting or inverted " +
             (dim == 2 ? "quadrilateral" : mesh.CellSize(c) == 5 ? "pyramid" : "hexahedron") +
             "); expected convex elements";
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
  if (nneg)
    for (int c = 0; c < nc; ++c) FlipCell(mesh, c);
  return "";
}

} // namespace signorini
