#include "io/map_header.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <sstream>

#include "core/errors.h"
#include "io/vertex_map.h"

namespace liftmap {
namespace {

/// Two triangles of a square.
Eigen::MatrixXi square() { return (Eigen::MatrixXi(2, 3) << 0, 1, 2, 0, 2, 3).finished(); }

TEST(MeshFingerprint, DependsOnConnectivityOnly) {
  const MeshFingerprint a = mesh_fingerprint(4, square());
  EXPECT_EQ(a.vertices, 4);
  EXPECT_EQ(a.faces, 2);
  EXPECT_EQ(mesh_fingerprint(4, square()), a) << "the same faces give the same fingerprint";
  Eigen::MatrixXi flipped = (Eigen::MatrixXi(2, 3) << 0, 1, 3, 1, 2, 3).finished();
  EXPECT_NE(mesh_fingerprint(4, flipped).connectivity, a.connectivity) << "another triangulation";
  Eigen::MatrixXi rotated = (Eigen::MatrixXi(2, 3) << 1, 2, 0, 0, 2, 3).finished();
  EXPECT_NE(mesh_fingerprint(4, rotated).connectivity, a.connectivity) << "another corner order";
  Eigen::MatrixXi reversed = square();
  reversed.col(1).swap(reversed.col(2));
  EXPECT_NE(mesh_fingerprint(4, reversed).connectivity, a.connectivity) << "reversed faces";
  EXPECT_NE(mesh_fingerprint(5, square()), a) << "another vertex count";
}

TEST(MeshFingerprint, TextRoundTrip) {
  const MeshFingerprint a = mesh_fingerprint(4, square());
  const std::string text = to_string(a);
  EXPECT_EQ(text.rfind("4 vertices, 2 faces, connectivity fnv1a64:", 0), 0U) << text;
  EXPECT_EQ(parse_mesh_fingerprint(text), a);
  EXPECT_EQ(parse_mesh_fingerprint(to_string({0, 0, 0})), (MeshFingerprint{0, 0, 0}));
  EXPECT_EQ(parse_mesh_fingerprint(to_string({7, 9, ~0ULL})), (MeshFingerprint{7, 9, ~0ULL}));
  for (const std::string& bad : std::vector<std::string>{
           "", "4 vertices", "4 vertices, 2 faces, connectivity fnv1a64:12", text + " extra", text + "0",
           "-4 vertices, 2 faces, connectivity fnv1a64:0123456789abcdef",
           "4 vertices, 2 faces, connectivity md5:0123456789abcdef", "4 vertices, 2 faces, connectivity fnv1a64:XYZ"}) {
    EXPECT_FALSE(parse_mesh_fingerprint(bad)) << bad;
  }
}

/// A map file of two points of faces 0 and 1 after `header` and before `footer`, read against `target`.
MapFile read_with(const std::string& header, const MeshOfMap& target, const std::string& footer = "") {
  std::istringstream in(header + "0 1 0 0\n1 0 1 0\n" + footer);
  return read_map_file(in, "m.txt", target);
}

TEST(ReadMapFile, ChecksTheTargetItsHeaderNames) {
  const MeshFingerprint a = mesh_fingerprint(4, square());
  const MeshFingerprint other{4, 2, a.connectivity ^ 1};
  const std::string header = "# map\n# source mesh: " + to_string(other) + "\n# target mesh: " + to_string(a) + "\n";
  const MapFile map = read_with(header, {"t.off", a});
  ASSERT_EQ(map.images.size(), 2U);
  EXPECT_EQ(map.meshes.source, other);
  EXPECT_EQ(map.meshes.target, a);
  const MeshFingerprint bigger{40, 76, 5};
  try {
    read_with(header, {"t.off", bigger});
    FAIL() << "another target mesh accepted";
  } catch (const InvalidInputError& e) {
    EXPECT_EQ(std::string(e.what()), "m.txt: made for a target mesh with " + to_string(a) + ", but t.off has " +
                                         to_string(bigger) + ": the map does not belong to this mesh");
  }
  EXPECT_THROW(read_with("", {"t.off", bigger}, "# target mesh: " + to_string(a) + "\n"), InvalidInputError)
      << "a line after the map lines is checked too";
  std::string upper = to_string(a);
  std::transform(upper.end() - 16, upper.end(), upper.end() - 16, [](unsigned char c) { return std::toupper(c); });
  EXPECT_EQ(read_with("# target mesh: " + upper + "\n", {"t.off", a}).meshes.target, a) << "upper-case digits";
}

TEST(RequireMapMesh, NamesTheSideAndBothFingerprints) {
  const MeshFingerprint a = mesh_fingerprint(4, square());
  const MeshFingerprint other{4, 2, a.connectivity ^ 1};
  const MapMeshes named{other, a};
  EXPECT_NO_THROW(require_map_mesh(named, MapSide::kSource, {"s.off", other}, "m.txt"));
  EXPECT_NO_THROW(require_map_mesh(named, MapSide::kTarget, {"t.off", a}, "m.txt"));
  EXPECT_NO_THROW(require_map_mesh({}, MapSide::kTarget, {"t.off", other}, "m.txt")) << "a file that names none";
  try {
    require_map_mesh(named, MapSide::kSource, {"s.off", a}, "m.txt");
    FAIL() << "another source mesh accepted";
  } catch (const InvalidInputError& e) {
    EXPECT_EQ(std::string(e.what()), "m.txt: made for a source mesh with " + to_string(other) + ", but s.off has " +
                                         to_string(a) +
                                         " (the same counts, other faces: a re-meshed or re-ordered mesh): the map "
                                         "does not belong to this mesh");
  }
}

TEST(MapHeaderOfText, FindsTheLinesAnywhereAtTheStartOfALine) {
  const MeshFingerprint a = mesh_fingerprint(4, square()), b{9, 14, 77};
  const std::string text = "\n# table\n1 2 3\n# target mesh: " + to_string(b) + "\r\n4 5 6 # source mesh: x\n" +
                           "# source mesh: " + to_string(a);
  const MapMeshes named = map_header_of_text(text, "p.txt");
  EXPECT_EQ(named.source, a);
  EXPECT_EQ(named.target, b);
  EXPECT_FALSE(map_header_of_text("1 2\n# other\n", "p.txt").source);
  try {
    map_header_of_text("1 2\n\n# source mesh: 3 vertices\n", "p.txt");
    FAIL() << "a malformed line accepted";
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()),
              "p.txt:3: '3 vertices' is not a mesh fingerprint ('V vertices, F faces, connectivity fnv1a64:X')");
  }
}

TEST(ReadMapFile, AcceptsFilesThatNameNoMesh) {
  // Maps of other tools, and of liftmap before its files named their meshes.
  EXPECT_EQ(read_with("# another tool\n", {"t.off", mesh_fingerprint(4, square())}).images.size(), 2U);
  EXPECT_EQ(read_with("", {"t.off", mesh_fingerprint(4, square())}).images.size(), 2U);
}

TEST(ReadMapFile, RejectsMalformedOrRepeatedMeshLines) {
  const MeshOfMap target{"t.off", mesh_fingerprint(4, square())};
  const std::string fp = to_string(target.fingerprint);
  const auto error_of = [&](const std::string& header) -> std::string {
    try {
      read_with(header, target);
    } catch (const IoError& e) {
      return e.what();
    }
    return "no IoError";
  };
  EXPECT_EQ(error_of("# target mesh: 4 vertices\n"),
            "m.txt:1: '4 vertices' is not a mesh fingerprint ('V vertices, F faces, connectivity fnv1a64:X')");
  EXPECT_EQ(error_of("# target mesh: " + fp + "\n# target mesh: " + fp + "\n"),
            "m.txt:2: a second '# target mesh' line");
  EXPECT_EQ(read_with("# target mesh: " + fp + " \r\n", target).images.size(), 2U) << "CRLF and trailing blanks";
}

TEST(ReadMapFile, WriteReadRoundTripNamesBothMeshes) {
  const std::string path = ::testing::TempDir() + "liftmap_test_map_header.txt";
  const MeshFingerprint s{10, 16, 123}, t = mesh_fingerprint(4, square());
  write_vertex_map(path, {SurfacePoint::in_face(FaceId(1), {0.2, 0.3, 0.5})}, "two\nlines", {s, t});
  const MapFile map = read_map_file(path, {"t.off", t});
  EXPECT_EQ(map.meshes.source, s);
  EXPECT_EQ(map.meshes.target, t);
  ASSERT_EQ(map.images.size(), 1U);
  EXPECT_EQ(map.images[0].bary[2], 0.5);
  EXPECT_EQ(read_vertex_map(path, 2).size(), 1U) << "read_vertex_map reads such files without checking the meshes";
}

}  // namespace
}  // namespace liftmap
