// Reading gmsh files (format 2.2 and 4.1) into the serial mesh, and the orientation and shape checks of cells;
// meshing a .geo in a child process, with its cell estimate.
#include "signorini/mesh/serial_mesh.hpp"

#include "signorini/mesh/geo_mesher.hpp"

#include "mesh/mesh_files.hpp"

#include <gmsh.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

namespace signorini {
namespace {

using test::MIXED_MESH_22;
using test::MIXED_MESH_41;
using test::TempDir;
using Tags = std::set<std::size_t>;

double SignedArea(const SerialMesh &mesh, int c) {
  const int n = mesh.CellSize(c);
  const int *v = &mesh.cell_nodes[mesh.cell_offsets[c]];
  double a = 0;
  for (int k = 0; k < n; ++k) {
    const double *p = &mesh.coords[2 * v[k]], *q = &mesh.coords[2 * v[(k + 1) % n]];
    a += p[0] * q[1] - q[0] * p[1];
  }
  return 0.5 * a;
}

const PhysicalGroup *FindGroup(const SerialMesh &mesh, const std::string &name) {
  for (const auto &g : mesh.groups)
    if (g.name == name) return &g;
  return nullptr;
}

Tags NodeTags(const SerialMesh &mesh, const std::vector<int> &nodes) {
  Tags tags;
  for (int v : nodes)
    tags.insert(mesh.node_tags[v]);
  return tags;
}

int CellWithTag(const SerialMesh &mesh, std::size_t tag) {
  const auto it = std::find(mesh.cell_tags.begin(), mesh.cell_tags.end(), tag);
  return it == mesh.cell_tags.end() ? -1 : (int)(it - mesh.cell_tags.begin());
}

/// Node tags of a cell, rotated to start at its smallest tag (cyclic order kept).
std::vector<std::size_t> CellNodeTags(const SerialMesh &mesh, int c) {
  std::vector<std::size_t> tags;
  for (int k = mesh.cell_offsets[c]; k < mesh.cell_offsets[c + 1]; ++k)
    tags.push_back(mesh.node_tags[mesh.cell_nodes[k]]);
  std::rotate(tags.begin(), std::min_element(tags.begin(), tags.end()), tags.end());
  return tags;
}

/// Checks the mixed mesh of mesh_files.hpp as read from either format.
void CheckMixedMesh(const SerialMesh &mesh) {
  EXPECT_EQ(mesh.dim, 2);
  ASSERT_EQ(mesh.NumNodes(), 6); // node 99 belongs to no cell
  ASSERT_EQ(mesh.coords.size(), 12u);
  EXPECT_EQ(Tags(mesh.node_tags.begin(), mesh.node_tags.end()), (Tags{11, 12, 13, 21, 22, 23}));
  const std::map<std::size_t, std::array<double, 2>> xy = {{11, {0, 0}}, {12, {1, 0}}, {13, {2, 0}},
                                                           {21, {0, 1}}, {22, {1, 1}}, {23, {2, 1}}};
  for (int v = 0; v < mesh.NumNodes(); ++v) {
    ASSERT_EQ(xy.count(mesh.node_tags[v]), 1u) << "unexpected node tag " << mesh.node_tags[v];
    EXPECT_EQ(mesh.coords[2 * v], xy.at(mesh.node_tags[v])[0]);
    EXPECT_EQ(mesh.coords[2 * v + 1], xy.at(mesh.node_tags[v])[1]);
  }

  ASSERT_EQ(mesh.NumCells(), 3);
  EXPECT_EQ(Tags(mesh.cell_tags.begin(), mesh.cell_tags.end()), (Tags{5, 6, 7}));
  const int quad = CellWithTag(mesh, 5), tri6 = CellWithTag(mesh, 6), tri7 = CellWithTag(mesh, 7);
  ASSERT_GE(quad, 0);
  ASSERT_GE(tri6, 0);
  ASSERT_GE(tri7, 0);
  EXPECT_EQ(CellNodeTags(mesh, quad), (std::vector<std::size_t>{11, 12, 22, 21}));
  EXPECT_EQ(CellNodeTags(mesh, tri6), (std::vector<std::size_t>{12, 13, 23}));
  EXPECT_EQ(CellNodeTags(mesh, tri7), (std::vector<std::size_t>{12, 23, 22}));
  EXPECT_DOUBLE_EQ(SignedArea(mesh, quad), 1.0);
  EXPECT_DOUBLE_EQ(SignedArea(mesh, tri6), 0.5);
  EXPECT_DOUBLE_EQ(SignedArea(mesh, tri7), 0.5);

  const PhysicalGroup *corner = FindGroup(mesh, "corner"), *bottom = FindGroup(mesh, "bottom"),
                      *left = FindGroup(mesh, "left"), *body = FindGroup(mesh, "body");
  ASSERT_TRUE(corner && bottom && left && body);
  EXPECT_EQ(corner->dim, 0);
  EXPECT_EQ(corner->tag, 4);
  EXPECT_EQ(NodeTags(mesh, corner->nodes), (Tags{13}));
  EXPECT_EQ(bottom->dim, 1);
  EXPECT_EQ(bottom->tag, 2);
  EXPECT_EQ(NodeTags(mesh, bottom->nodes), (Tags{11, 12, 13}));
  EXPECT_TRUE(std::is_sorted(bottom->nodes.begin(), bottom->nodes.end()));
  ASSERT_EQ(bottom->edges.size(), 4u);
  std::set<Tags> edges;
  for (std::size_t e = 0; e < bottom->edges.size(); e += 2)
    edges.insert({mesh.node_tags[bottom->edges[e]], mesh.node_tags[bottom->edges[e + 1]]});
  EXPECT_EQ(edges, (std::set<Tags>{{11, 12}, {12, 13}}));
  EXPECT_EQ(left->dim, 1);
  EXPECT_EQ(NodeTags(mesh, left->nodes), (Tags{11, 21}));
  EXPECT_EQ(left->edges.size(), 2u);
  EXPECT_EQ(body->dim, 2);
  EXPECT_EQ(body->tag, 1);
  EXPECT_EQ(std::set<int>(body->cells.begin(), body->cells.end()), (std::set<int>{0, 1, 2}));
  // A group of cells lists no nodes of its own: they are its cells' nodes.
  EXPECT_TRUE(body->nodes.empty());
  std::vector<int> cell_nodes;
  for (int c : body->cells)
    for (int k = mesh.cell_offsets[c]; k < mesh.cell_offsets[c + 1]; ++k) cell_nodes.push_back(mesh.cell_nodes[k]);
  EXPECT_EQ(NodeTags(mesh, cell_nodes), (Tags{11, 12, 13, 21, 22, 23}));
}

TEST(ReadGmsh, MixedMeshInFormat22) {
  TempDir dir;
  SerialMesh mesh;
  ASSERT_EQ(ReadGmsh(dir.Write("mixed22.msh", MIXED_MESH_22), 1.0, mesh), "");
  CheckMixedMesh(mesh);
  // A physical group without a name is named by its number.
  const PhysicalGroup *right = FindGroup(mesh, "9");
  ASSERT_NE(right, nullptr);
  EXPECT_EQ(right->dim, 1);
  EXPECT_EQ(right->tag, 9);
  EXPECT_EQ(NodeTags(mesh, right->nodes), (Tags{13, 23}));
  EXPECT_EQ(mesh.groups.size(), 5u);
}

TEST(ReadGmsh, MixedMeshInFormat41) {
  TempDir dir;
  SerialMesh mesh;
  ASSERT_EQ(ReadGmsh(dir.Write("mixed41.msh", MIXED_MESH_41), 1.0, mesh), "");
  CheckMixedMesh(mesh);
  // Format 4.1 lists nodes by entity, and they keep the order of the file.
  EXPECT_EQ(mesh.node_tags, (std::vector<std::size_t>{11, 13, 21, 12, 22, 23}));
  EXPECT_EQ(mesh.groups.size(), 4u);
}

TEST(ReadGmsh, ClockwiseFileIsReadCounterClockwise) {
  std::string text = MIXED_MESH_22;
  for (const auto &[from, to] : {std::pair<std::string, std::string>{"11 12 22 21\n", "21 22 12 11\n"},
                                 {"12 13 23\n", "23 13 12\n"},
                                 {"12 23 22\n", "22 23 12\n"}}) {
    const auto pos = text.find(from);
    ASSERT_NE(pos, std::string::npos);
    text.replace(pos, from.size(), to);
  }
  TempDir dir;
  SerialMesh mesh;
  ASSERT_EQ(ReadGmsh(dir.Write("clockwise.msh", text), 1.0, mesh), "");
  ASSERT_EQ(mesh.NumCells(), 3);
  for (int c = 0; c < mesh.NumCells(); ++c)
    EXPECT_GT(SignedArea(mesh, c), 0.0) << "cell " << c;
  EXPECT_EQ(CellNodeTags(mesh, CellWithTag(mesh, 5)), (std::vector<std::size_t>{11, 12, 22, 21}));
}

TEST(ReadGmsh, InvertedElementInAFileIsAnError) {
  std::string text = MIXED_MESH_41;
  const auto pos = text.find("7 12 23 22\n");
  ASSERT_NE(pos, std::string::npos);
  text.replace(pos, 11, "7 12 22 23\n");
  TempDir dir;
  SerialMesh mesh;
  const std::string error = ReadGmsh(dir.Write("inverted.msh", text), 1.0, mesh);
  EXPECT_NE(error.find("inverted"), std::string::npos) << error;
  EXPECT_NE(error.find("element 7"), std::string::npos) << error;
}

TEST(ReadGmsh, RepositoryMeshes) {
  SerialMesh beam;
  ASSERT_EQ(ReadGmsh(SIGNORINI_SOURCE_DIR "/meshes/beam.msh", 1.0, beam), "");
  EXPECT_EQ(beam.NumNodes(), 205);
  std::set<std::string> names;
  for (const auto &g : beam.groups)
    names.insert(g.name);
  EXPECT_EQ(names, (std::set<std::string>{"tip", "bottom", "right", "top", "left", "body"}));
  const PhysicalGroup *top = FindGroup(beam, "top"), *left = FindGroup(beam, "left"), *body = FindGroup(beam, "body");
  ASSERT_TRUE(top && left && body);
  EXPECT_EQ(top->dim, 1);
  EXPECT_EQ(body->dim, 2);
  EXPECT_EQ((int)body->cells.size(), beam.NumCells());
  EXPECT_GT(top->nodes.size(), 2u);
  for (int v : top->nodes)
    EXPECT_NEAR(beam.coords[2 * v + 1], 1.0, 1e-12);
  for (int v : left->nodes)
    EXPECT_NEAR(beam.coords[2 * v], 0.0, 1e-12);
  EXPECT_EQ(top->edges.size(), 2 * (top->nodes.size() - 1));
  for (int c = 0; c < beam.NumCells(); ++c)
    ASSERT_GT(SignedArea(beam, c), 0.0) << "cell " << c;

  SerialMesh hertz;
  ASSERT_EQ(ReadGmsh(SIGNORINI_SOURCE_DIR "/meshes/hertz.msh", 1.0, hertz), "");
  names.clear();
  for (const auto &g : hertz.groups)
    names.insert(g.name);
  EXPECT_EQ(names, (std::set<std::string>{"top_centre", "contact_point", "top", "contact", "body"}));
  const PhysicalGroup *centre = FindGroup(hertz, "top_centre");
  ASSERT_NE(centre, nullptr);
  EXPECT_EQ(centre->dim, 0);
  ASSERT_EQ(centre->nodes.size(), 1u);
  EXPECT_NEAR(hertz.coords[2 * centre->nodes[0]], 0.0, 1e-12);
  EXPECT_NEAR(hertz.coords[2 * centre->nodes[0] + 1], 0.0, 1e-12);
}

/// The cells as lists of their vertices' coordinates in their order, sorted (what a mesh is, whatever the file's
/// numbering of nodes and elements: format 2.2 numbers the elements anew).
std::vector<std::vector<double>> CellCoordinates(const SerialMesh &mesh) {
  std::vector<std::vector<double>> cells(mesh.NumCells());
  for (int c = 0; c < mesh.NumCells(); ++c)
    for (int k = mesh.cell_offsets[c]; k < mesh.cell_offsets[c + 1]; ++k)
      for (int d = 0; d < mesh.dim; ++d)
        cells[c].push_back(mesh.coords[mesh.dim * mesh.cell_nodes[k] + d]);
  std::sort(cells.begin(), cells.end());
  return cells;
}

/// Number of cells of each size (vertices per cell).
std::map<int, int> CellKinds(const SerialMesh &mesh) {
  std::map<int, int> kinds;
  for (int c = 0; c < mesh.NumCells(); ++c)
    kinds[mesh.CellSize(c)]++;
  return kinds;
}

TEST(ReadGmsh, ConformingTetrahedraPyramidsAndHexahedraInEveryFormat) {
  const std::string msh = SIGNORINI_SOURCE_DIR "/meshes/cube_mixed_conforming.msh";
  SerialMesh ref;
  ASSERT_EQ(ReadGmsh(msh, 1.0, ref), "");
  // Hexahedra on x in [0, 1] (5 x 5 x 4), tetrahedra on x in [1, 2], and one pyramid on each quadrilateral of the
  // shared face x = 1 (5 x 4), its apex among the tetrahedra.
  const auto kinds = CellKinds(ref);
  EXPECT_EQ(kinds.at(8), 100);
  EXPECT_EQ(kinds.at(5), 20);
  EXPECT_GT(kinds.at(4), 100);
  EXPECT_EQ(kinds.size(), 3u);
  for (int c = 0; c < ref.NumCells(); ++c) {
    if (ref.CellSize(c) != 5) continue;
    const int *v = &ref.cell_nodes[ref.cell_offsets[c]];
    for (int a = 0; a < 4; ++a)
      EXPECT_EQ(ref.coords[3 * v[a]], 1.0) << "base vertex " << a << " of pyramid " << ref.cell_tags[c];
    EXPECT_GT(ref.coords[3 * v[4]], 1.0) << "apex of pyramid " << ref.cell_tags[c];
  }
  // The same mesh written by gmsh in format 2.2 (ASCII and binary) and 4.1 binary reads the same.
  TempDir dir;
  const std::vector<std::pair<double, int>> formats = {{2.2, 0}, {2.2, 1}, {4.1, 1}};
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::open(msh);
  for (const auto &[version, binary] : formats) {
    gmsh::option::setNumber("Mesh.MshFileVersion", version);
    gmsh::option::setNumber("Mesh.Binary", binary);
    gmsh::write(dir.Path("v" + std::to_string(version) + "_" + std::to_string(binary) + ".msh"));
  }
  gmsh::finalize();
  for (const auto &[version, binary] : formats) {
    SCOPED_TRACE("format " + std::to_string(version) + (binary ? " binary" : " ASCII"));
    SerialMesh mesh;
    ASSERT_EQ(ReadGmsh(dir.Path("v" + std::to_string(version) + "_" + std::to_string(binary) + ".msh"), 1.0, mesh),
              "");
    EXPECT_EQ(CellCoordinates(mesh), CellCoordinates(ref));
    EXPECT_EQ(mesh.groups.size(), ref.groups.size());
  }
  // The .geo, meshed in a child process, has the same hexahedra and pyramids.
  SerialMesh geo;
  ASSERT_EQ(ReadGmsh(SIGNORINI_SOURCE_DIR "/meshes/cube_mixed_conforming.geo", 1.0, geo), "");
  EXPECT_EQ(CellKinds(geo).at(5), 20);
  EXPECT_EQ(CellKinds(geo).at(8), 100);
}

TEST(ReadGmsh, UnreadableFilesAreErrors) {
  TempDir dir;
  SerialMesh mesh;
  EXPECT_NE(ReadGmsh(dir.Path("missing.msh"), 1.0, mesh).find("cannot open"), std::string::npos);
  EXPECT_NE(ReadGmsh(dir.Write("empty.msh", ""), 1.0, mesh).find("empty"), std::string::npos);
  EXPECT_NE(ReadGmsh(dir.Write("text.msh", "hello\n"), 1.0, mesh).find("$MeshFormat"), std::string::npos);
  // Only line elements: no cells.
  const std::string lines = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n2 1 0 0\n$EndNodes\n"
                            "$Elements\n1\n1 1 2 1 1 1 2\n$EndElements\n";
  EXPECT_NE(ReadGmsh(dir.Write("lines.msh", lines), 1.0, mesh).find("no triangles"), std::string::npos);
  // Quadratic triangle (gmsh type 9): not a linear element.
  const std::string quadratic = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n6\n1 0 0 0\n2 1 0 0\n3 0 1 0\n"
                                "4 0.5 0 0\n5 0.5 0.5 0\n6 0 0.5 0\n$EndNodes\n"
                                "$Elements\n1\n1 9 2 1 1 1 2 3 4 5 6\n$EndElements\n";
  const std::string error = ReadGmsh(dir.Write("quadratic.msh", quadratic), 1.0, mesh);
  EXPECT_NE(error.find("expected linear triangles"), std::string::npos) << error;
}

/// The mixed mesh of mesh_files.hpp built in memory: nodes 0..5 at (0,0) (1,0) (2,0) (0,1) (1,1) (2,1) plus
/// node 6 at (0.2,0.2); cells with tags 5, 6, 7, ...
SerialMesh MakeMesh(const std::vector<std::vector<int>> &cells) {
  SerialMesh mesh;
  mesh.coords = {0, 0, 1, 0, 2, 0, 0, 1, 1, 1, 2, 1, 0.2, 0.2};
  for (std::size_t v = 0; v < mesh.coords.size() / 2; ++v)
    mesh.node_tags.push_back(v + 1);
  for (std::size_t c = 0; c < cells.size(); ++c) {
    mesh.cell_nodes.insert(mesh.cell_nodes.end(), cells[c].begin(), cells[c].end());
    mesh.cell_offsets.push_back((int)mesh.cell_nodes.size());
    mesh.cell_tags.push_back(5 + c);
  }
  return mesh;
}

TEST(CheckAndOrientCells, CounterClockwiseMeshIsUnchanged) {
  SerialMesh mesh = MakeMesh({{0, 1, 4, 3}, {1, 2, 5}, {1, 5, 4}});
  const std::vector<int> before = mesh.cell_nodes;
  EXPECT_EQ(CheckAndOrientCells(mesh), "");
  EXPECT_EQ(mesh.cell_nodes, before);
}

TEST(CheckAndOrientCells, ClockwiseMeshIsFlippedSilently) {
  SerialMesh mesh = MakeMesh({{3, 4, 1, 0}, {5, 2, 1}, {4, 5, 1}});
  EXPECT_EQ(CheckAndOrientCells(mesh), "");
  for (int c = 0; c < mesh.NumCells(); ++c)
    EXPECT_GT(SignedArea(mesh, c), 0.0) << "cell " << c;
  EXPECT_EQ(mesh.cell_nodes, (std::vector<int>{0, 1, 4, 3, 1, 2, 5, 1, 5, 4}));
}

TEST(CheckAndOrientCells, OneInvertedElementIsAnError) {
  SerialMesh mesh = MakeMesh({{0, 1, 4, 3}, {1, 2, 5}, {1, 4, 5}});
  const std::string error = CheckAndOrientCells(mesh);
  EXPECT_NE(error.find("1 inverted element(s) of 3"), std::string::npos) << error;
  EXPECT_NE(error.find("element 7"), std::string::npos) << error;
  // The minority is reported whichever orientation it has.
  SerialMesh flipped = MakeMesh({{3, 4, 1, 0}, {5, 2, 1}, {1, 5, 4}});
  const std::string error2 = CheckAndOrientCells(flipped);
  EXPECT_NE(error2.find("element 7"), std::string::npos) << error2;
}

TEST(CheckAndOrientCells, ZeroAreaElementsAreErrors) {
  SerialMesh collinear = MakeMesh({{0, 1, 4, 3}, {0, 1, 2}});
  const std::string error = CheckAndOrientCells(collinear);
  EXPECT_NE(error.find("element 6 has zero area"), std::string::npos) << error;
  SerialMesh repeated = MakeMesh({{0, 1, 4, 3}, {1, 2, 2}});
  EXPECT_NE(CheckAndOrientCells(repeated).find("zero area"), std::string::npos);
  // A quadrilateral with three collinear corners is a degenerate (triangle-shaped) quadrilateral.
  SerialMesh degenerate = MakeMesh({{0, 1, 2, 5}});
  EXPECT_NE(CheckAndOrientCells(degenerate).find("zero area"), std::string::npos);
}

TEST(CheckAndOrientCells, NonConvexQuadrilateralsAreErrors) {
  SerialMesh bow_tie = MakeMesh({{0, 1, 3, 4}});
  const std::string error = CheckAndOrientCells(bow_tie);
  EXPECT_NE(error.find("element 5 is not convex"), std::string::npos) << error;
  SerialMesh dart = MakeMesh({{1, 2, 5}, {0, 1, 6, 3}});
  const std::string error2 = CheckAndOrientCells(dart);
  EXPECT_NE(error2.find("element 6 is not convex"), std::string::npos) << error2;
}

const char *SQUARE_GEO = "Point(1) = {0, 0, 0, 0.1}; Point(2) = {1, 0, 0, 0.1}; Point(3) = {1, 1, 0, 0.1};\n"
                         "Point(4) = {0, 1, 0, 0.1}; Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4};\n"
                         "Line(4) = {4, 1}; Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};\n"
                         "Physical Surface(\"body\") = {1}; Physical Curve(\"bottom\") = {1};\n";

TEST(EstimateCells, EquilateralTrianglesOfTheMeanBoundarySize) {
  // A unit square with 40 boundary segments: h = 0.1, an equilateral triangle of side h has area sqrt(3)/4 h^2.
  EXPECT_NEAR(EstimateCells(1.0, 4.0, 40), 4 / (std::sqrt(3.0) * 0.01), 1e-9);
  EXPECT_EQ(EstimateCells(1.0, 0.0, 0), 0);
  EXPECT_GT(DefaultMaxCells(), 1e5);
}

TEST(MeshGeo, SquareIsMeshedInAChildAndReadBack) {
  TempDir dir;
  SerialMesh mesh;
  ASSERT_EQ(ReadGmsh(dir.Write("square.geo", SQUARE_GEO), 1.0, mesh, 1e6), "");
  // 0.1 on a unit square: about 230 triangles (gmsh's frontal mesher lands near the estimate).
  EXPECT_GT(mesh.NumCells(), 100);
  EXPECT_LT(mesh.NumCells(), 500);
  std::set<std::string> names;
  for (const auto &g : mesh.groups) names.insert(g.name);
  EXPECT_EQ(names, (std::set<std::string>{"body", "bottom"}));
}

TEST(MeshGeo, RefusesAMeshEstimatedAboveTheLimit) {
  TempDir dir;
  SerialMesh mesh;
  const std::string error = ReadGmsh(dir.Write("square.geo", SQUARE_GEO), 1e-2, mesh, 1e5);
  EXPECT_NE(error.find("square.geo' would have about 2.31e+06 cells"), std::string::npos) << error;
  EXPECT_NE(error.find("more than -mesh_max_cells 1e+05"), std::string::npos) << error;
}

} // namespace
} // namespace signorini

namespace signorini {
namespace {

/// A 3D serial mesh on the corners of the unit cube (node = x + 2 y + 4 z) with the given cells.
SerialMesh MakeMesh3D(const std::vector<std::vector<int>> &cells) {
  SerialMesh mesh;
  mesh.dim = 3;
  for (int k = 0; k < 8; ++k) {
    mesh.coords.insert(mesh.coords.end(), {double(k & 1), double((k >> 1) & 1), double((k >> 2) & 1)});
    mesh.node_tags.push_back(k + 1);
  }
  for (std::size_t c = 0; c < cells.size(); ++c) {
    mesh.cell_nodes.insert(mesh.cell_nodes.end(), cells[c].begin(), cells[c].end());
    mesh.cell_offsets.push_back((int)mesh.cell_nodes.size());
    mesh.cell_tags.push_back(10 + c);
  }
  return mesh;
}

TEST(CheckAndOrientCells3D, NegativeTetrahedraAndHexahedraAreFlippedAndAMinorityIsAnError) {
  // Gmsh order of the unit cube (node = x + 2 y + 4 z): bottom 0 1 3 2, top 4 5 7 6.
  const std::vector<int> hex = {0, 1, 3, 2, 4, 5, 7, 6}, hex_mirrored = {4, 5, 7, 6, 0, 1, 3, 2};
  const std::vector<int> tet = {0, 1, 2, 4}, tet_mirrored = {0, 2, 1, 4};
  SerialMesh good = MakeMesh3D({hex, tet});
  EXPECT_EQ(CheckAndOrientCells(good), "");
  EXPECT_EQ(good.cell_nodes, MakeMesh3D({hex, tet}).cell_nodes);
  SerialMesh mirrored = MakeMesh3D({hex_mirrored, tet_mirrored});
  EXPECT_EQ(CheckAndOrientCells(mirrored), "");
  // Flipped back to a positive orientation: the same checks then pass without a change.
  SerialMesh again = mirrored;
  EXPECT_EQ(CheckAndOrientCells(again), "");
  EXPECT_EQ(again.cell_nodes, mirrored.cell_nodes);
  EXPECT_NE(mirrored.cell_nodes, MakeMesh3D({hex_mirrored, tet_mirrored}).cell_nodes);
  SerialMesh mixed = MakeMesh3D({hex, tet, tet_mirrored});
  const std::string error = CheckAndOrientCells(mixed);
  EXPECT_NE(error.find("1 inverted element(s) of 3 (e.g. element 12)"), std::string::npos) << error;
}

TEST(CheckAndOrientCells3D, PyramidsAreFlippedWithTheMeshAndChecked) {
  // On the unit cube's corners (node = x + 2 y + 4 z): base 0 1 3 2 (z = 0, counter-clockwise seen from above), apex
  // 4 above; mirrored: its base reversed.
  const std::vector<int> pyramid = {0, 1, 3, 2, 4}, pyramid_mirrored = {0, 2, 3, 1, 4};
  const std::vector<int> tet = {0, 1, 2, 4}, tet_mirrored = {0, 2, 1, 4};
  SerialMesh good = MakeMesh3D({pyramid, tet});
  EXPECT_EQ(CheckAndOrientCells(good), "");
  EXPECT_EQ(good.cell_nodes, MakeMesh3D({pyramid, tet}).cell_nodes);
  SerialMesh mirrored = MakeMesh3D({pyramid_mirrored, tet_mirrored});
  EXPECT_EQ(CheckAndOrientCells(mirrored), "");
  EXPECT_EQ(mirrored.cell_nodes, MakeMesh3D({pyramid, tet}).cell_nodes);
  SerialMesh minority = MakeMesh3D({pyramid_mirrored, tet});
  EXPECT_NE(CheckAndOrientCells(minority).find("1 inverted element(s) of 2"), std::string::npos)
      << CheckAndOrientCells(minority);
  SerialMesh flat = MakeMesh3D({{0, 1, 3, 2, 1}}); // apex on the base
  EXPECT_NE(CheckAndOrientCells(flat).find("element 10 has zero volume"), std::string::npos)
      << CheckAndOrientCells(flat);
  SerialMesh bowtie = MakeMesh3D({{0, 1, 2, 3, 4}}); // self-intersecting base
  EXPECT_NE(CheckAndOrientCells(bowtie).find("element 10 is not convex (self-intersecting or inverted pyramid)"),
            std::string::npos)
      << CheckAndOrientCells(bowtie);
}

TEST(CheckAndOrientCells3D, FlatAndTwistedCellsAreErrors) {
  SerialMesh flat = MakeMesh3D({{0, 1, 2, 3}}); // four nodes in the plane z = 0
  EXPECT_NE(CheckAndOrientCells(flat).find("element 10 has zero volume"), std::string::npos);
  SerialMesh twisted = MakeMesh3D({{0, 1, 3, 2, 4, 5, 6, 7}}); // top quadrilateral self-intersecting
  EXPECT_NE(CheckAndOrientCells(twisted).find("element 10 is not convex"), std::string::npos)
      << CheckAndOrientCells(twisted);
}

} // namespace
} // namespace signorini

namespace signorini {
namespace {

TEST(ReadGmshElements, SurfaceOfTrianglesAndQuadrilateralsWithItsGroup) {
  for (const char *group : {"floor", ""}) {
    ElementSet set;
    ASSERT_EQ(ReadGmshElements(SIGNORINI_SOURCE_DIR "/meshes/flat_obstacle.msh", 2, group, set), "");
    int triangles = 0, quads = 0;
    for (int e = 0; e < set.NumElements(); ++e)
      (set.Size(e) == 3 ? triangles : quads) += 1;
    EXPECT_EQ(triangles, 24);
    EXPECT_EQ(quads, 4);
    EXPECT_EQ(set.node_tags.size(), 25u); // the 4 x 5 nodes of the triangles, 5 more at x = 1.5
    for (std::size_t i = 0; i < set.node_tags.size(); ++i)
      EXPECT_EQ(set.X(i)[2], 0.0);
  }
}

TEST(ReadGmshElements, PolylineKeepsTheFileOrderOfItsNodes) {
  ElementSet set;
  ASSERT_EQ(ReadGmshElements(SIGNORINI_SOURCE_DIR "/meshes/arc_obstacle.msh", 1, "arc", set), "");
  ASSERT_EQ(set.NumElements(), 30);
  // The arc runs from 150 to 30 degrees: each line starts where the previous one ends, left to right.
  for (int e = 0; e < 30; ++e) {
    const int *v = &set.nodes[set.offsets[e]];
    EXPECT_LT(set.X(v[0])[0], set.X(v[1])[0]);
    if (e > 0) {
      EXPECT_EQ(v[0], set.nodes[set.offsets[e - 1] + 1]);
    }
  }
}

TEST(ReadGmshElements, GroupAndDimensionErrors) {
  ElementSet set;
  const std::string flat = SIGNORINI_SOURCE_DIR "/meshes/flat_obstacle.msh";
  EXPECT_NE(ReadGmshElements(flat, 2, "roof", set).find("has no physical group 'roof'; expected one of: 'floor' (2D)"),
            std::string::npos);
  EXPECT_NE(ReadGmshElements(flat, 1, "floor", set).find("physical group 'floor' is 2D; expected a 1D group"),
            std::string::npos);
  EXPECT_NE(ReadGmshElements(flat, 1, "", set).find("has only 28 element(s) of dimension 2; expected 2-node line"),
            std::string::npos);
  EXPECT_NE(ReadGmshElements(SIGNORINI_SOURCE_DIR "/meshes/none.msh", 2, "", set).find("cannot open obstacle mesh"),
            std::string::npos);
}

} // namespace
} // namespace signorini
