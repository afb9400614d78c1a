#include "io/read_mesh.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "common/test_meshes.h"
#include "core/errors.h"
#include "io/write_mesh.h"

namespace liftmap {
namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("liftmap_test_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

std::string error_of(const std::string& path) {
  try {
    read_mesh(path);
  } catch (const IoError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ReadMesh, OffAndObjAgree) {
  const TriangleMesh off = read_mesh(testing::test_data("good/octahedron.off"));
  const TriangleMesh obj = read_mesh(testing::test_data("good/octahedron.obj"));
  EXPECT_EQ(off.V, obj.V);
  EXPECT_EQ(off.F, obj.F) << "OBJ's 1-based, negative and v/vt/vn indices must give the same faces";
}

TEST(ReadMesh, WriteReadRoundTripIsExactInEveryFormat) {
  const TriangleMesh cow = testing::read_demo_mesh("cow.off");
  for (const char* ext : {".obj", ".off", ".ply"}) {
    SCOPED_TRACE(ext);
    const std::string path = temp_path(std::string("cow") + ext);
    write_mesh(path, cow.V, cow.F);
    const TriangleMesh back = read_mesh(path);
    EXPECT_EQ(back.F, cow.F);
    EXPECT_EQ(back.V, cow.V) << "17 significant digits must round-trip doubles exactly";
    std::filesystem::remove(path);
  }
}

// STL stores each triangle's corners; reading must merge them back into shared vertices.
void write_stl(const std::string& path, const TriangleMesh& m, bool binary) {
  std::ofstream out(path, std::ios::binary);
  if (binary) {
    const std::string header(80, ' ');
    out.write(header.data(), 80);
    const auto n = static_cast<uint32_t>(m.F.rows());
    out.write(reinterpret_cast<const char*>(&n), 4);
    for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
      float data[12] = {0, 0, 0};
      for (int k = 0; k < 3; ++k) {
        for (int c = 0; c < 3; ++c) data[3 + 3 * k + c] = static_cast<float>(m.V(m.F(f, k), c));
      }
      out.write(reinterpret_cast<const char*>(data), sizeof(data));
      const uint16_t attr = 0;
      out.write(reinterpret_cast<const char*>(&attr), 2);
    }
  } else {
    out << "solid test\n";
    for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
      out << "facet normal 0 0 0\nouter loop\n";
      for (int k = 0; k < 3; ++k) {
        out << "vertex " << static_cast<float>(m.V(m.F(f, k), 0)) << ' ' << static_cast<float>(m.V(m.F(f, k), 1)) << ' '
            << static_cast<float>(m.V(m.F(f, k), 2)) << '\n';
      }
      out << "endloop\nendfacet\n";
    }
    out << "endsolid test\n";
  }
}

TEST(ReadMesh, StlAsciiAndBinaryMergeDuplicateVertices) {
  const TriangleMesh oct = read_mesh(testing::test_data("good/octahedron.off"));
  for (bool binary : {false, true}) {
    SCOPED_TRACE(binary ? "binary" : "ascii");
    const std::string path = temp_path(binary ? "oct_bin.stl" : "oct_ascii.stl");
    write_stl(path, oct, binary);
    const TriangleMesh back = read_mesh(path);
    EXPECT_EQ(back.V.rows(), 6) << "24 corners must merge into 6 vertices";
    ASSERT_EQ(back.F.rows(), 8);
    for (Eigen::Index f = 0; f < 8; ++f) {
      for (int k = 0; k < 3; ++k) EXPECT_EQ(back.V.row(back.F(f, k)), oct.V.row(oct.F(f, k)));
    }
    std::filesystem::remove(path);
  }
}

TEST(ReadMesh, ErrorsNameTheFileAndLine) {
  EXPECT_NE(error_of(testing::test_data("bad/not_a_number.off")).find("not_a_number.off:3: 'zero' is not a number"),
            std::string::npos);
  EXPECT_NE(error_of(testing::test_data("bad/quad_face.obj")).find("quad_face.obj:5:"), std::string::npos);
  EXPECT_NE(error_of(testing::test_data("bad/huge_counts.off")).find("huge_counts.off:2:"), std::string::npos);
  EXPECT_NE(error_of("/nonexistent/mesh.off").find("/nonexistent/mesh.off: no such file"), std::string::npos);
  EXPECT_NE(error_of(testing::test_data("good")).find("unknown mesh format"), std::string::npos);
}

TEST(ReadMesh, NonFiniteCoordinatesAreReadSoThatValidationCanNameThem) {
  const TriangleMesh m = read_mesh(testing::test_data("bad/nan_coordinate.off"));
  EXPECT_TRUE(std::isnan(m.V(4, 1)));
}

}  // namespace
}  // namespace liftmap
