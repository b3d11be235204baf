// The distributed mesh on one rank: group lookup by name, group and boundary edges with their orientation, the
// error for an unknown group, the -mesh_ options, and no leaked PETSc objects.
#include "signorini/mesh/mesh.hpp"

#include "mesh/mesh_files.hpp"
#include "petsc_helpers.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace signorini {
namespace {

using test::ErrorCapture;
using test::ScopedOptions;
using test::TempDir;

MeshOptions Options(const std::string &file) {
  MeshOptions opts;
  opts.file = file;
  return opts;
}

/// The error message of Mesh::Create on the mesh file `name` (written with `text`, or missing when text is null),
/// which must fail.
std::string CreateError(const char *name, const char *text) {
  TempDir dir;
  Mesh mesh;
  ErrorCapture capture;
  EXPECT_NE(mesh.Create(PETSC_COMM_SELF, Options(text ? dir.Write(name, text) : dir.Path(name))), 0) << name;
  return capture.Message();
}

class MixedMesh : public ::testing::Test {
protected:
  void SetUp() override {
    ASSERT_EQ(mesh_.Create(PETSC_COMM_SELF, Options(dir_.Write("mixed.msh", test::MIXED_MESH_22))), 0);
  }

  /// Coordinates of a list of local vertices, as a sorted set.
  std::set<std::pair<double, double>> Points(const std::vector<PetscInt> &vertices) const {
    std::set<std::pair<double, double>> points;
    for (PetscInt v : vertices)
      points.insert({mesh_.X(v)[0], mesh_.X(v)[1]});
    return points;
  }

  TempDir dir_;
  Mesh mesh_;
};

TEST_F(MixedMesh, SizesAndFileOrder) {
  EXPECT_EQ(mesh_.Dim(), 2);
  EXPECT_EQ(mesh_.NumGlobalNodes(), 6);
  EXPECT_EQ(mesh_.NumGlobalCells(), 3);
  ASSERT_EQ(mesh_.NumLocalVertices(), 6);
  ASSERT_EQ(mesh_.NumLocalCells(), 3);
  // The file as read on its own: the distributed mesh must hold its nodes and cells, and its tags in file order.
  SerialMesh serial;
  ASSERT_EQ(ReadGmsh(dir_.Write("mixed_again.msh", test::MIXED_MESH_22), 1.0, serial), "");
  EXPECT_EQ(mesh_.NodeTagsBlock(), serial.node_tags);
  EXPECT_EQ(mesh_.CellTagsBlock(), serial.cell_tags);
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v) {
    EXPECT_TRUE(mesh_.Owned(v));
    const PetscInt o = mesh_.VertexOriginal(v);
    EXPECT_EQ(mesh_.X(v)[0], serial.coords[2 * o]);
    EXPECT_EQ(mesh_.X(v)[1], serial.coords[2 * o + 1]);
  }
  for (PetscInt c = 0; c < mesh_.NumLocalCells(); ++c) {
    PetscInt n;
    const PetscInt *cv = mesh_.CellVertices(c, n);
    const int o = (int)mesh_.CellOriginal(c);
    ASSERT_EQ(n, serial.CellSize(o));
    std::multiset<PetscInt> local, file;
    for (PetscInt k = 0; k < n; ++k)
      local.insert(mesh_.VertexOriginal(cv[k]));
    for (int k = serial.cell_offsets[o]; k < serial.cell_offsets[o + 1]; ++k)
      file.insert(serial.cell_nodes[k]);
    EXPECT_EQ(local, file) << "cell " << c;
  }
}

TEST_F(MixedMesh, GroupVerticesByName) {
  const std::vector<std::string> names = mesh_.GroupNames();
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()),
            (std::set<std::string>{"corner", "bottom", "left", "body", "9"}));
  std::vector<PetscInt> vertices;
  ASSERT_EQ(mesh_.GroupVertices("bottom", vertices), 0);
  EXPECT_EQ(Points(vertices), (std::set<std::pair<double, double>>{{0, 0}, {1, 0}, {2, 0}}));
  ASSERT_EQ(mesh_.GroupVertices("left", vertices), 0);
  EXPECT_EQ(Points(vertices), (std::set<std::pair<double, double>>{{0, 0}, {0, 1}}));
  ASSERT_EQ(mesh_.GroupVertices("corner", vertices), 0);
  EXPECT_EQ(Points(vertices), (std::set<std::pair<double, double>>{{2, 0}}));
  ASSERT_EQ(mesh_.GroupVertices("body", vertices), 0);
  EXPECT_EQ(vertices.size(), 6u);
  ASSERT_EQ(mesh_.GroupVertices("9", vertices), 0);
  EXPECT_EQ(Points(vertices), (std::set<std::pair<double, double>>{{2, 0}, {2, 1}}));
}

TEST_F(MixedMesh, UnknownGroupIsAnErrorListingTheKnownNames) {
  std::vector<PetscInt> vertices;
  ErrorCapture capture;
  EXPECT_NE(mesh_.GroupVertices("contact", vertices), 0);
  const std::string &message = capture.Message();
  EXPECT_NE(message.find("'contact'"), std::string::npos) << message;
  for (const char *name : {"corner", "bottom", "left", "body", "9"})
    EXPECT_NE(message.find(name), std::string::npos) << name << " missing from: " << message;
}

TEST_F(MixedMesh, GroupFacesHaveTheBodyOnTheirLeft) {
  std::vector<Face> edges;
  ASSERT_EQ(mesh_.GroupFaces("bottom", edges), 0);
  ASSERT_EQ(edges.size(), 2u);
  for (const auto &e : edges) {
    EXPECT_EQ(mesh_.X(e.v[0])[1], 0.0);
    EXPECT_EQ(mesh_.X(e.v[1])[1], 0.0);
    EXPECT_EQ(mesh_.X(e.v[1])[0] - mesh_.X(e.v[0])[0], 1.0); // along +x: the body (y > 0) is on the left
  }
  ASSERT_EQ(mesh_.GroupFaces("left", edges), 0);
  ASSERT_EQ(edges.size(), 1u);
  EXPECT_EQ(mesh_.X(edges[0].v[0])[1], 1.0); // downwards: the body (x > 0) is on the left
  EXPECT_EQ(mesh_.X(edges[0].v[1])[1], 0.0);
}

TEST_F(MixedMesh, GroupFacesRequireACurve) {
  std::vector<Face> edges;
  for (const char *name : {"body", "corner"}) {
    ErrorCapture capture;
    EXPECT_NE(mesh_.GroupFaces(name, edges), 0) << name;
    EXPECT_NE(capture.Message().find("expected a physical curve"), std::string::npos) << capture.Message();
  }
}

TEST_F(MixedMesh, BoundaryFacesEncloseTheBodyCounterClockwise) {
  std::vector<PetscInt> vertices;
  ASSERT_EQ(mesh_.BoundaryVertices(vertices), 0);
  EXPECT_EQ(vertices.size(), 6u);
  std::vector<Face> edges;
  ASSERT_EQ(mesh_.BoundaryFaces(edges), 0);
  ASSERT_EQ(edges.size(), 6u);
  double area = 0; // shoelace over the oriented boundary: +area for a counter-clockwise boundary
  for (const auto &e : edges)
    area += 0.5 * (mesh_.X(e.v[0])[0] * mesh_.X(e.v[1])[1] - mesh_.X(e.v[1])[0] * mesh_.X(e.v[0])[1]);
  EXPECT_DOUBLE_EQ(area, 2.0);
}

TEST(Mesh, CreateAndDestroyLeaveNoPetscObjects) {
  TempDir dir;
  const MeshOptions opts = Options(dir.Write("mixed.msh", test::MIXED_MESH_41));
  {
    Mesh warm_up;
    ASSERT_EQ(warm_up.Create(PETSC_COMM_SELF, opts), 0);
  }
  const double before = test::PetscMemoryInUse();
  ASSERT_GT(before, 0.0) << "PETSc memory tracing (-malloc_debug) is off";
  {
    Mesh mesh;
    ASSERT_EQ(mesh.Create(PETSC_COMM_SELF, opts), 0);
    std::vector<PetscInt> vertices;
    std::vector<Face> edges;
    ASSERT_EQ(mesh.GroupVertices("bottom", vertices), 0);
    ASSERT_EQ(mesh.GroupFaces("bottom", edges), 0);
    ASSERT_EQ(mesh.BoundaryFaces(edges), 0);
    std::vector<double> per_vertex(mesh.NumLocalVertices(), 1.0);
    ASSERT_EQ(mesh.SumShared(per_vertex), 0);
    EXPECT_EQ(per_vertex, std::vector<double>(6, 1.0)); // one rank: nothing shared
  }
  EXPECT_EQ(test::PetscMemoryInUse(), before);
}

TEST(Mesh, BeamGroupsSitOnTheirEdges) {
  Mesh mesh;
  ASSERT_EQ(mesh.Create(PETSC_COMM_SELF, Options(SIGNORINI_SOURCE_DIR "/meshes/beam.msh")), 0);
  std::vector<PetscInt> top, left;
  ASSERT_EQ(mesh.GroupVertices("top", top), 0);
  ASSERT_EQ(mesh.GroupVertices("left", left), 0);
  ASSERT_GT(top.size(), 2u);
  ASSERT_GT(left.size(), 1u);
  for (PetscInt v : top)
    EXPECT_NEAR(mesh.X(v)[1], 1.0, 1e-12);
  for (PetscInt v : left)
    EXPECT_NEAR(mesh.X(v)[0], 0.0, 1e-12);
  std::vector<Face> edges;
  ASSERT_EQ(mesh.GroupFaces("top", edges), 0);
  EXPECT_EQ(edges.size(), top.size() - 1);
  for (const auto &e : edges)
    EXPECT_LT(mesh.X(e.v[1])[0], mesh.X(e.v[0])[0]); // top edge runs in -x, body below
}

/// Checks that faces tile the surface of the box [0, hi] outwards: each lies on the side its normal points to, their
/// outward vector areas cancel and the absolute values of their components sum to the box's surface area.
void ExpectBoxFaces(const Mesh &mesh, const std::vector<Face> &faces, const double hi[3], double area) {
  double sum[3] = {0, 0, 0}, total = 0;
  for (const Face &f : faces) {
    double n[3], centre[3] = {0, 0, 0};
    mesh.FaceNormal(f, n);
    for (int a = 0; a < f.n; ++a)
      for (int d = 0; d < 3; ++d)
        centre[d] += mesh.X(f.v[a])[d] / f.n;
    // On the side with outward normal e_d (or -e_d), the centre lies at hi[d] (or 0) along d.
    for (int d = 0; d < 3; ++d) {
      sum[d] += n[d];
      total += std::abs(n[d]);
      if (std::abs(n[d]) > 1e-12) {
        EXPECT_NEAR(centre[d], n[d] > 0 ? hi[d] : 0.0, 1e-14);
      }
    }
  }
  for (int d = 0; d < 3; ++d)
    EXPECT_NEAR(sum[d], 0.0, 1e-13);
  EXPECT_NEAR(total, area, 1e-13);
}

TEST(Mesh3D, CubeFacesAreOrientedOutwardsAndTileTheBoundary) {
  for (const char *file : {"cube.msh", "cube_tet.msh"}) {
    SCOPED_TRACE(file);
    Mesh mesh;
    ASSERT_EQ(mesh.Create(PETSC_COMM_SELF, Options(std::string(SIGNORINI_SOURCE_DIR "/meshes/") + file)), 0);
    EXPECT_EQ(mesh.Dim(), 3);
    std::vector<Face> faces;
    ASSERT_EQ(mesh.BoundaryFaces(faces), 0);
    for (const Face &f : faces)
      EXPECT_EQ(f.n, std::string(file) == "cube.msh" ? 4 : 3);
    // Six unit faces: the outward vector areas cancel and their absolute values sum to 6.
    const double one[3] = {1, 1, 1};
    ExpectBoxFaces(mesh, faces, one, 6.0);
    ASSERT_EQ(mesh.GroupFaces("bottom", faces), 0);
    double bottom = 0;
    for (const Face &f : faces) {
      double n[3];
      mesh.FaceNormal(f, n);
      bottom += n[2];
    }
    EXPECT_NEAR(bottom, -1.0, 1e-14); // outward: -z
    ErrorCapture capture;
    EXPECT_NE(mesh.GroupFaces("body", faces), 0);
    EXPECT_NE(capture.Message().find("expected a physical surface (dimension 2)"), std::string::npos)
        << capture.Message();
  }
}

TEST(Mesh3D, ConformingMixedMeshJoinsItsCellsThroughEveryInteriorFace) {
  // meshes/cube_mixed_conforming.msh: the box [0, 2] x [0, 1] x [0, 1] of hexahedra, pyramids and tetrahedra. DMPlex
  // joins two cells through a face when both have a face on the same vertices: the boundary faces are then exactly
  // the box's faces, of total area 10, oriented outwards (a pyramid's face not joined to its neighbour's would be a
  // boundary face inside the box).
  Mesh mesh;
  ASSERT_EQ(mesh.Create(PETSC_COMM_SELF, Options(SIGNORINI_SOURCE_DIR "/meshes/cube_mixed_conforming.msh")), 0);
  std::vector<Face> faces;
  ASSERT_EQ(mesh.BoundaryFaces(faces), 0);
  const double hi[3] = {2, 1, 1};
  ExpectBoxFaces(mesh, faces, hi, 10.0);
  // Every vertex on the box's surface is a boundary vertex, and no other.
  std::vector<PetscInt> boundary;
  ASSERT_EQ(mesh.BoundaryVertices(boundary), 0);
  std::size_t on_surface = 0;
  for (PetscInt v = 0; v < mesh.NumLocalVertices(); ++v) {
    bool surface = false;
    for (int d = 0; d < 3; ++d)
      surface = surface || mesh.X(v)[d] == 0.0 || mesh.X(v)[d] == hi[d];
    on_surface += surface;
  }
  EXPECT_EQ(boundary.size(), on_surface);
  // DMPlex's own checks: cones of the right size for each cell type, faces consistent with their cells' cones.
  EXPECT_EQ(DMPlexCheckSkeleton(mesh.Dm(), 0), 0);
  EXPECT_EQ(DMPlexCheckFaces(mesh.Dm(), 0), 0);
}

TEST(Mesh3D, FacesOfAPyramidAreOrientedOutwards) {
  // One pyramid (base the unit square at z = 0, apex (0.3, 0.6, 0.8)), its base and its four sides as physical
  // surfaces, each given in a node order against the outward one: the faces come back outwards, closing the surface.
  const char *pyramid = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
3
2 1 "base"
2 2 "sides"
3 3 "body"
$EndPhysicalNames
$Nodes
5
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
5 0.3 0.6 0.8
$EndNodes
$Elements
6
1 3 2 1 1 1 2 3 4
2 2 2 2 2 1 5 2
3 2 2 2 2 2 5 3
4 2 2 2 2 3 5 4
5 2 2 2 2 4 5 1
6 7 2 3 3 1 2 3 4 5
$EndElements
)";
  TempDir dir;
  Mesh mesh;
  ASSERT_EQ(mesh.Create(PETSC_COMM_SELF, Options(dir.Write("pyramid.msh", pyramid))), 0);
  ASSERT_EQ(mesh.NumLocalCells(), 1);
  std::vector<Face> base, sides, boundary;
  ASSERT_EQ(mesh.GroupFaces("base", base), 0);
  ASSERT_EQ(mesh.GroupFaces("sides", sides), 0);
  ASSERT_EQ(mesh.BoundaryFaces(boundary), 0);
  ASSERT_EQ(base.size(), 1u);
  EXPECT_EQ(base[0].n, 4);
  ASSERT_EQ(sides.size(), 4u);
  EXPECT_EQ(boundary.size(), 5u);
  double n[3], sum[3] = {0, 0, 0};
  mesh.FaceNormal(base[0], n);
  EXPECT_NEAR(n[0], 0.0, 1e-15);
  EXPECT_NEAR(n[1], 0.0, 1e-15);
  EXPECT_NEAR(n[2], -1.0, 1e-15); // outward: -z, area 1
  for (const Face &f : sides) {
    EXPECT_EQ(f.n, 3);
    mesh.FaceNormal(f, n);
    double out = 0; // from the base's centre (0.5, 0.5, 0) to the face's centroid
    for (int d = 0; d < 3; ++d) {
      double c = 0;
      for (int a = 0; a < 3; ++a)
        c += mesh.X(f.v[a])[d] / 3;
      out += n[d] * (c - (d < 2 ? 0.5 : 0.0));
      sum[d] += n[d];
    }
    EXPECT_GT(out, 0.0);
  }
  EXPECT_NEAR(sum[0], 0.0, 1e-15);
  EXPECT_NEAR(sum[1], 0.0, 1e-15);
  EXPECT_NEAR(sum[2], 1.0, 1e-15); // the sides close the surface with the base
}

TEST(Mesh, FoldedCellsAreAnErrorNamingThem) {
  // Two counter-clockwise triangles on the same side of the edge (1, 2) they share: each valid, together folded.
  const char *folded = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
4
1 0 0 0
2 1 0 0
3 0 1 0
4 0.4 0.3 0
$EndNodes
$Elements
2
7 2 2 0 1 1 2 3
8 2 2 0 1 1 2 4
$EndElements
)";
  const std::string message = CreateError("folded.msh", folded);
  EXPECT_NE(message.find("elements 7 and 8 overlap: they lie on the same side of the edge they share"),
            std::string::npos)
      << message;
}

TEST(Mesh, GroupLineThatIsNoCellEdgeIsAnError) {
  // A unit square of two triangles split along (1, 3); the physical curve's line (2, 4) crosses it.
  const char *crossing = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
2
1 5 "cut"
2 6 "body"
$EndPhysicalNames
$Nodes
4
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
$EndNodes
$Elements
3
7 2 2 6 1 1 2 3
8 2 2 6 1 1 3 4
9 1 2 5 1 2 4
$EndElements
)";
  const std::string message = CreateError("crossing.msh", crossing);
  EXPECT_NE(message.find("crossing.msh': a line element of physical curve 'cut' is not an edge of any cell"),
            std::string::npos)
      << message;
}

TEST(Mesh, MissingFileIsAnError) {
  const std::string message = CreateError("none.msh", nullptr);
  EXPECT_NE(message.find("none.msh"), std::string::npos) << message;
}

TEST(MeshOptions, ValuesAreReadAndValidated) {
  {
    ScopedOptions options({{"-mesh_file", "a.geo"}, {"-mesh_size_factor", "0.5"}, {"-mesh_partitioner", "simple"}});
    MeshOptions opts;
    ASSERT_EQ(ReadMeshOptions(PETSC_COMM_SELF, "default.msh", opts), 0);
    EXPECT_EQ(opts.file, "a.geo");
    EXPECT_EQ(opts.size_factor, 0.5);
    EXPECT_EQ(opts.partitioner, "simple");
  }
  {
    MeshOptions opts;
    ASSERT_EQ(ReadMeshOptions(PETSC_COMM_SELF, "default.msh", opts), 0);
    EXPECT_EQ(opts.file, "default.msh");
    EXPECT_EQ(opts.partitioner, "metis");
  }
  for (const auto &[name, value] : {std::pair<const char *, const char *>{"-mesh_size_factor", "0"},
                                    {"-mesh_size_factor", "-1"},
                                    {"-mesh_size_factor", "inf"},
                                    {"-mesh_partitioner", "chaco"}}) {
    SCOPED_TRACE(std::string(name) + " " + value);
    ScopedOptions options({{name, value}});
    ErrorCapture capture;
    MeshOptions opts;
    EXPECT_NE(ReadMeshOptions(PETSC_COMM_SELF, "default.msh", opts), 0);
    EXPECT_NE(capture.Message().find(name), std::string::npos) << capture.Message();
  }
  // The meshing options with a .msh would be ignored: an error naming the option and what it applies to.
  for (const auto &[name, value] : {std::pair<const char *, const char *>{"-mesh_size_factor", "0.5"},
                                    {"-mesh_max_cells", "10"}}) {
    SCOPED_TRACE(name);
    ScopedOptions options({{"-mesh_file", "a.msh"}, {name, value}});
    ErrorCapture capture;
    MeshOptions opts;
    EXPECT_NE(ReadMeshOptions(PETSC_COMM_SELF, "default.msh", opts), 0);
    EXPECT_NE(capture.Message().find(std::string(name) + " " + value + " applies to meshing a .geo file only"),
              std::string::npos) << capture.Message();
  }
}

} // namespace
} // namespace signorini
