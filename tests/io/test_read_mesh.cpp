#include "io/read_mesh.h"

#include <gtest/gtest.h>

#include <CGAL/IO/STL.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <array>
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

TEST(ReadMesh, StlVerticesAreNumberedInOrderOfFirstAppearanceAsCgalDid) {
  // Landmark files of STL meshes rely on this numbering (README, "File formats"): liftmap's reader replaced
  // CGAL's and must number the merged corners as it did.
  const TriangleMesh cow = testing::read_demo_mesh("cow.off");
  for (bool binary : {false, true}) {
    SCOPED_TRACE(binary ? "binary" : "ascii");
    const std::string path = temp_path(binary ? "cow_bin.stl" : "cow_ascii.stl");
    write_stl(path, cow, binary);
    std::ifstream in(path, std::ios::binary);
    std::vector<CGAL::Simple_cartesian<double>::Point_3> points;
    std::vector<std::array<std::size_t, 3>> triangles;
    ASSERT_TRUE(CGAL::IO::read_STL(in, points, triangles));
    const TriangleMesh ours = read_mesh(path);
    ASSERT_EQ(ours.V.rows(), static_cast<Eigen::Index>(points.size()));
    ASSERT_EQ(ours.F.rows(), static_cast<Eigen::Index>(triangles.size()));
    for (size_t i = 0; i < points.size(); ++i) {
      const auto r = static_cast<Eigen::Index>(i);
      EXPECT_EQ(ours.V.row(r), Eigen::RowVector3d(points[i].x(), points[i].y(), points[i].z())) << "vertex " << i;
    }
    for (size_t f = 0; f < triangles.size(); ++f) {
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(ours.F(static_cast<Eigen::Index>(f), k), static_cast<int>(triangles[f][static_cast<size_t>(k)]));
      }
    }
    std::filesystem::remove(path);
  }
}

std::string data_error_of(const std::string& data, const std::string& name) {
  try {
    read_mesh_data(data, name);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "no error";
}

TEST(ReadMesh, CountsThatDoNotMatchTheContentAreNamedAsSuch) {
  const std::string tetra = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n";
  EXPECT_EQ(read_mesh_data(tetra, "t.off").F.rows(), 4);
  std::string one_too_many = tetra;
  one_too_many.replace(one_too_many.find("4 4 0"), 5, "4 3 0");
  EXPECT_EQ(data_error_of(one_too_many, "t.off"),
            "t.off:10: the header announces 4 vertices and 3 faces, but the file goes on: the counts do not match the "
            "content");
  std::string one_line = tetra;
  std::replace(one_line.begin(), one_line.end(), '\n', ' ');
  EXPECT_NE(data_error_of(one_line, "t.off").find("t.off:1: 28 more values after the 'vertices faces edges' counts"),
            std::string::npos)
      << data_error_of(one_line, "t.off");
  // A binary STL whose count is too small for its size (it used to be read as an open mesh).
  std::string stl(84 + 2 * 50, '\0');
  stl[80] = 1;
  EXPECT_NE(data_error_of(stl, "s.stl")
                .find("s.stl: the binary STL header announces 1 triangles (134 bytes), but the "
                      "file has 184 bytes (room for 2 triangles)"),
            std::string::npos)
      << data_error_of(stl, "s.stl");
}

TEST(ReadMesh, AByteOrderMarkIsSkipped) {
  const std::string tetra = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n";
  const TriangleMesh with = read_mesh_data("\xEF\xBB\xBF" + tetra, "t.off");
  const TriangleMesh without = read_mesh_data(tetra, "t.off");
  EXPECT_EQ(with.V, without.V);
  EXPECT_EQ(with.F, without.F);
  const std::string obj = "\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  EXPECT_EQ(read_mesh_data(obj, "t.obj").F.rows(), 1);
}

TEST(ReadMesh, PlyNegativeIndexAndNonFiniteCoordinateAreNamed) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  EXPECT_EQ(data_error_of(header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 -5\n", "p.ply"),
            "p.ply: face 0 references vertex -5, but there are 3 vertices");
  try {
    read_mesh_data(header + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "p.ply");
    FAIL() << "no error";
  } catch (const InvalidInputError& e) {
    EXPECT_STREQ(e.what(), "p.ply:11: non-finite coordinate 'nan'");
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
