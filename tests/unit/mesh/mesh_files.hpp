// Small gmsh files written by the mesh tests: the same mixed triangle/quadrilateral mesh in format 2.2 and 4.1.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace signorini::test {

/// A private temporary directory, removed with its files at the end of the scope.
class TempDir {
public:
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "signorini_unit_XXXXXX").string();
    if (mkdtemp(pattern.data())) path_ = pattern;
    EXPECT_FALSE(path_.empty()) << "cannot create a temporary directory";
  }
  TempDir(const TempDir &) = delete;
  TempDir &operator=(const TempDir &) = delete;
  ~TempDir() {
    std::error_code ec;
    if (!path_.empty()) std::filesystem::remove_all(path_, ec);
  }
  /// Path of a file in the directory.
  std::string Path(const std::string &name) const { return path_ + "/" + name; }
  /// Writes text to a file of the directory and returns its path.
  std::string Write(const std::string &name, const std::string &text) const {
    const std::string file = Path(name);
    std::ofstream(file) << text;
    return file;
  }

private:
  std::string path_;
};

/// A 2 x 1 rectangle: one quadrilateral (element 5: nodes 11 12 22 21) on [0,1]x[0,1] and two triangles
/// (elements 6, 7) on [1,2]x[0,1]. Node tags are not contiguous and node 99 belongs to no cell. Physical groups:
/// point "corner" (node 13), curves "bottom" (11-12-13) and "left" (11-21), surface "body" (all cells); the 2.2
/// file adds an unnamed physical curve 9 on the right edge (13-23).
inline const char *MIXED_MESH_22 = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
4
0 4 "corner"
1 2 "bottom"
1 3 "left"
2 1 "body"
$EndPhysicalNames
$Nodes
7
11 0 0 0
12 1 0 0
13 2 0 0
99 5 5 0
21 0 1 0
22 1 1 0
23 2 1 0
$EndNodes
$Elements
8
1 15 2 4 2 13
2 1 2 2 1 11 12
3 1 2 2 1 12 13
4 1 2 3 2 11 21
8 1 2 9 3 13 23
5 3 2 1 1 11 12 22 21
6 2 2 1 1 12 13 23
7 2 2 1 1 12 23 22
$EndElements
)";

inline const char *MIXED_MESH_41 = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
4
0 4 "corner"
1 2 "bottom"
1 3 "left"
2 1 "body"
$EndPhysicalNames
$Entities
3 2 1 0
1 0 0 0 0
2 2 0 0 1 4
3 0 1 0 0
1 0 0 0 2 0 0 1 2 2 1 -2
2 0 0 0 0 1 0 1 3 2 1 -3
1 0 0 0 2 1 0 1 1 2 1 2
$EndEntities
$Nodes
5 7 11 99
0 1 0 1
11
0 0 0
0 2 0 1
13
2 0 0
0 3 0 1
21
0 1 0
1 1 0 1
12
1 0 0
2 1 0 3
22
23
99
1 1 0
2 1 0
5 5 0
$EndNodes
$Elements
5 7 1 7
0 2 15 1
1 13
1 1 1 2
2 11 12
3 12 13
1 2 1 1
4 11 21
2 1 3 1
5 11 12 22 21
2 1 2 2
6 12 13 23
7 12 23 22
$EndElements
)";

} // namespace signorini::test
