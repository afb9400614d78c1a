#include "io/landmarks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <vector>

#include "common/test_meshes.h"
#include "core/errors.h"

namespace liftmap {
namespace {

TEST(Landmarks, ReadsPairsWithCommentsAndLineNumbers) {
  const Landmarks lm = read_landmarks(testing::test_data("good/landmarks.txt"), 6, 6);
  ASSERT_EQ(lm.a.size(), 3U);
  EXPECT_EQ(lm.a[0].vertex.idx, 4);
  EXPECT_EQ(lm.b[2].vertex.idx, 1);
  EXPECT_EQ(lm.line[0], 2);
  EXPECT_EQ(lm.line[2], 4);
}

TEST(Landmarks, AByteOrderMarkIsSkipped) {
  // It used to give "'\xEF\xBB\xBF117' is not a vertex index", the mark invisible in the message.
  std::istringstream in(
      "\xEF\xBB\xBF"
      "117 3\n5 4\n");
  const Landmarks lm = read_landmarks(in, "bom.txt", 200, 200);
  ASSERT_EQ(lm.a.size(), 2U);
  EXPECT_EQ(lm.a[0].vertex.idx, 117);
}

TEST(Landmarks, WriteReadRoundTrip) {
  const TriangleMesh oct = read_mesh(testing::test_data("good/octahedron.off"));
  Landmarks lm;
  for (int i = 0; i < 6; ++i) {
    lm.a.push_back(SurfacePoint::at_vertex(VertexId(i)));
    lm.b.push_back(SurfacePoint::in_face(FaceId(i), {0.1 + 0.01 * i, 1.0 / 3, 1 - (0.1 + 0.01 * i) - 1.0 / 3}));
  }
  lm.a.push_back(SurfacePoint::in_face(FaceId(7), {0.5, 0, 0.5}));  // on an edge
  lm.b.push_back(SurfacePoint::at_vertex(VertexId(0)));
  const std::string path = (std::filesystem::temp_directory_path() / "liftmap_test_landmarks.txt").string();
  write_landmarks(path, lm);
  const Landmarks back = read_landmarks(path, oct.V, oct.F, oct.V, oct.F);
  ASSERT_EQ(back.a.size(), lm.a.size());
  for (size_t i = 0; i < lm.a.size(); ++i) {
    for (const auto& [p, q] : {std::pair{lm.a[i], back.a[i]}, std::pair{lm.b[i], back.b[i]}}) {
      ASSERT_EQ(p.kind, q.kind) << i;
      if (p.kind == SurfacePoint::Kind::kVertex) {
        EXPECT_EQ(p.vertex, q.vertex);
      } else {
        EXPECT_EQ(p.face, q.face);
        EXPECT_EQ(p.bary, q.bary);  // the shortest round-trip text: exactly
      }
    }
  }
  std::filesystem::remove(path);
}

TEST(Landmarks, ReadsFacePointsAnd3DPoints) {
  const TriangleMesh oct = read_mesh(testing::test_data("good/octahedron.off"));
  std::istringstream in(
      "4 f0:0.6,0.2,0.2\n"                       // line 1: vertex, face point
      "f1:0.25,0.25,0.5 0.2,0.3,0.5\n"           // line 2: face point, 3D point on face 0
      "f2:0,1,0 f3:2e-10,0.5,0.5\n"              // line 3: a corner (vertex 3); 2e-10 of the height from a side
      "f4:0.5,0,0.5 2,2,2\n"                     // line 4: on an edge; a 3D point far from the surface
      "f5:1e-13,0.4,0.6 f6:0.3,0.7,1e-14\n"      // line 5: rounding off a side: on it, without a warning
      "f7:0.0005,0.4995,0.5 f2:0.2,0.2,0.6\n");  // line 6: 5e-4 of the height from a side: moved, with a warning
  const Landmarks lm = read_landmarks(in, "lm.txt", oct.V, oct.F, oct.V, oct.F);
  ASSERT_EQ(lm.a.size(), 6U);
  EXPECT_EQ(lm.a[5].bary, (std::array<double, 3>{0, 0.4995 / 0.9995, 0.5 / 0.9995}));
  EXPECT_EQ(lm.a[4].bary[0], 0.0);
  EXPECT_EQ(lm.b[4].bary[2], 0.0);
  EXPECT_EQ(lm.b[4].bary[0] + lm.b[4].bary[1], 1.0);
  EXPECT_EQ(lm.a[0].kind, SurfacePoint::Kind::kVertex);
  EXPECT_EQ(lm.a[0].vertex.idx, 4);
  ASSERT_EQ(lm.b[0].kind, SurfacePoint::Kind::kFace);
  EXPECT_EQ(lm.b[0].face.idx, 0);
  EXPECT_DOUBLE_EQ(lm.b[0].bary[0], 0.6);
  // The 3D point (0.2, 0.3, 0.5) is a point of face 0 (x + y + z = 1, corners 0, 2, 4): located exactly there.
  ASSERT_EQ(lm.b[1].kind, SurfacePoint::Kind::kFace);
  EXPECT_EQ(lm.b[1].face.idx, 0);
  const Eigen::Vector3d x = testing::position(oct, lm.b[1]);
  EXPECT_LT((x - Eigen::Vector3d(0.2, 0.3, 0.5)).norm(), 1e-15);
  EXPECT_EQ(lm.a[2].kind, SurfacePoint::Kind::kVertex);
  EXPECT_EQ(lm.a[2].vertex.idx, 3);  // corner 1 of face 2 (1 3 4)
  ASSERT_EQ(lm.b[2].kind, SurfacePoint::Kind::kFace);
  EXPECT_NEAR(lm.b[2].bary[0] + lm.b[2].bary[1] + lm.b[2].bary[2], 1.0, 1e-15);
  ASSERT_EQ(lm.a[3].kind, SurfacePoint::Kind::kFace);
  EXPECT_EQ(lm.a[3].bary[1], 0.0);  // exactly on the edge
  // (2, 2, 2) is nearest to the centre of face 0, far from the surface: a warning naming the line, not an error.
  EXPECT_EQ(lm.b[3].face.idx, 0);
  EXPECT_NEAR(lm.b[3].bary[0], 1.0 / 3, 1e-15);
  ASSERT_EQ(lm.warnings.size(), 3U);
  EXPECT_NE(lm.warnings[0].find("lm.txt:3: the landmark on mesh B is within 0.001 of its face's height from a side of "
                                "face 3: moved onto the side, by 2"),
            std::string::npos)
      << lm.warnings[0];
  EXPECT_NE(lm.warnings[1].find("lm.txt:4: the point 2,2,2"), std::string::npos) << lm.warnings[1];
  EXPECT_NE(lm.warnings[2].find("lm.txt:6: the landmark on mesh A is within 0.001"), std::string::npos)
      << lm.warnings[2];
  EXPECT_EQ(lm.line[3], 4);
}

TEST(Landmarks, RejectsMalformedSurfacePointsWithTheLine) {
  const TriangleMesh oct = read_mesh(testing::test_data("good/octahedron.off"));
  const std::pair<const char*, const char*> cases[] = {
      {"f3 1", "lm.txt:2: 'f3' is not a face point 'f<face>:<b0>,<b1>,<b2>'"},
      {"fx:1,0,0 1", "lm.txt:2: 'x' in 'fx:1,0,0' is not a face index"},
      {"f-1:1,0,0 1", "lm.txt:2: '-1' in 'f-1:1,0,0' is not a face index"},
      {"f8:1,0,0 1", "lm.txt:2: face 8 is out of range for mesh A (8 faces)"},
      {"1 f0:0.5,0.5", "lm.txt:2: 'f0:0.5,0.5' is not a face point"},
      {"1 f0:nan,0.5,0.5", "lm.txt:2: barycentric coordinate nan is not finite"},
      {"1 f0:inf,0,0", "lm.txt:2: barycentric coordinate inf is not finite"},
      {"1 f0:-0.5,1,0.5", "lm.txt:2: barycentric coordinate -0.5 is negative: the point is outside face 0"},
      {"1 f0:1.5,-0.25,-0.25", "lm.txt:2: barycentric coordinate 1.5 is greater than 1"},
      {"1 f0:0.5,0.5,0.5", "lm.txt:2: barycentric coordinates sum to 1.5, not 1"},
      {"1 f0:0.5,one,0.5", "lm.txt:2: 'one' is not a number (in '0.5,one,0.5')"},
      {"1 f0:0.5,0.25,0.25,0", "lm.txt:2: '0.25,0' is not a number"},
      {"1,2 1", "lm.txt:2: '1,2' is not a 3D point 'x,y,z'"},
      {"1,2,nan 1", "lm.txt:2: coordinate nan of '1,2,nan' is not finite"},
      {"1,2,1e999 1", "lm.txt:2: '1e999' is out of range"},
      {"e3:0.5 1", "lm.txt:2: 'e3:0.5' is not a landmark of mesh A"},
      {"-3 1", "lm.txt:2: negative vertex index '-3' for mesh A"},
      // Two landmarks at one point of one side, written differently: an error naming both lines.
      {"f0:1,0,0 1", "lm.txt:2: vertex 0 of mesh A is already a landmark (line 1)"},
      {"1 f0:0.2,0.3,0.5", "lm.txt:2: the landmark f0:0.2,0.3,0.5 of mesh B is at the same point as the one of line 1"},
      {"1 0.2,0.3,0.5", "lm.txt:2: the landmark f0:"},
      {"1 f4:0,0.5,0.5", "lm.txt:2: the landmark f4:0,0.5,0.5 of mesh B is at the same point as the one of line 1"},
      // Two landmarks of one side 2.8e-10 apart in a face of size 0.93: too close to cut apart.
      {"1 f0:0.2,0.3000000002,0.4999999998",
       "of mesh B is 2.82843e-10 from the one of line 1, under 1e-06 of the size of their face (0.930605): too close "
       "to cut apart"},
      {"1 0.2,0.3000000002,0.4999999998", "of mesh B is 2.82843e-10 from the one of line 1, under 1e-06"},
  };
  for (const auto& [second_line, message] : cases) {
    // Line 1 puts A's landmark on vertex 0 and B's on face 0 (0.2, 0.3, 0.5), which is also the 3D point
    // (0.2, 0.3, 0.5); f4:0,0.5,0.5 and f7:0.5,0,0.5 are both the midpoint of the edge from vertex 0 to 5.
    const std::string first =
        std::string(second_line).find("f4:") != std::string::npos ? "0 f7:0.5,0,0.5\n" : "0 f0:0.2,0.3,0.5\n";
    std::istringstream in(first + second_line + "\n");
    try {
      read_landmarks(in, "lm.txt", oct.V, oct.F, oct.V, oct.F);
      ADD_FAILURE() << second_line << " was accepted";
    } catch (const InvalidInputError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << second_line << ": " << e.what();
    }
  }
  // 1e-5 of the face apart is far enough, inside a face and on an edge (closer to a vertex or a side than 1e-3 of
  // the face, a point is moved onto it, and then is that vertex or on that side).
  for (const char* text :
       {"0 f0:0.2,0.3,0.5\n1 f0:0.2,0.30001,0.49999\n", "f0:0.5,0.5,0 0\nf0:0.50001,0.49999,0 1\n"}) {
    std::istringstream near(text);
    EXPECT_NO_THROW(read_landmarks(near, "lm.txt", oct.V, oct.F, oct.V, oct.F)) << text;
  }
  // Without the meshes, only vertex indices.
  std::istringstream in("0 1\n1 f0:0.2,0.3,0.5\n");
  try {
    read_landmarks(in, "lm.txt", 6, 6);
    ADD_FAILURE() << "a face point was accepted without the meshes";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("lm.txt:2: 'f0:0.2,0.3,0.5' is a surface point"), std::string::npos)
        << e.what();
  }
}

// Surface points given as arrays (Python's dict of faces and barycentric coordinates) pass the checks and the snapping
// of a file's face points, with messages that name the row.
TEST(Landmarks, SurfacePointsFromArraysAreCheckedAsAFilesFacePoints) {
  const TriangleMesh oct = read_mesh(testing::test_data("good/octahedron.off"));
  std::istringstream in(
      "4 f0:0.6,0.2,0.2\n"
      "f2:0,1,0 f3:2e-10,0.5,0.5\n"
      "f7:0.0005,0.4995,0.5 0.2,0.3,0.5\n");
  const Landmarks file = read_landmarks(in, "lm.txt", oct.V, oct.F, oct.V, oct.F);
  // The same landmarks as face points (vertex 4 as a corner of face 0 (0 2 4), vertex 3 as corner 1 of face 2).
  const std::vector<SurfacePoint> a{SurfacePoint::in_face(FaceId(0), {0, 0, 1}),
                                    SurfacePoint::in_face(FaceId(2), {0, 1, 0}),
                                    SurfacePoint::in_face(FaceId(7), {0.0005, 0.4995, 0.5})};
  const std::vector<SurfacePoint> b{SurfacePoint::in_face(FaceId(0), {0.6, 0.2, 0.2}),
                                    SurfacePoint::in_face(FaceId(3), {2e-10, 0.5, 0.5}),
                                    SurfacePoint::in_face(FaceId(0), {0.2, 0.3, 0.5})};
  const Landmarks arrays = make_landmarks(a, b, "landmarks", oct.V, oct.F, oct.V, oct.F);
  ASSERT_EQ(arrays.a.size(), 3U);
  for (size_t i = 0; i < 3; ++i) {
    for (const auto& [x, y] : {std::pair{arrays.a[i], file.a[i]}, std::pair{arrays.b[i], file.b[i]}}) {
      ASSERT_EQ(x.kind, y.kind) << "row " << i;
      if (x.kind == SurfacePoint::Kind::kVertex) {
        EXPECT_EQ(x.vertex.idx, y.vertex.idx) << "row " << i;
      } else {
        EXPECT_EQ(x.face.idx, y.face.idx) << "row " << i;
        for (size_t k = 0; k < 3; ++k) EXPECT_NEAR(x.bary[k], y.bary[k], 1e-15) << "row " << i;
      }
    }
  }
  EXPECT_EQ(arrays.a[0].vertex.idx, 4);
  EXPECT_EQ(arrays.a[1].vertex.idx, 3);
  EXPECT_EQ(arrays.b[1].bary[0], 0.0) << "2e-10 of the height from a side: moved onto it";
  ASSERT_EQ(arrays.warnings.size(), 2U);
  EXPECT_NE(arrays.warnings[0].find("landmarks: row 1: the landmark on mesh B is within 0.001"), std::string::npos)
      << arrays.warnings[0];
  EXPECT_NE(arrays.warnings[1].find("landmarks: row 2: the landmark on mesh A is within 0.001"), std::string::npos)
      << arrays.warnings[1];
  // Vertex points pass as they are.
  const Landmarks vertices =
      make_landmarks({SurfacePoint::at_vertex(VertexId(0)), SurfacePoint::at_vertex(VertexId(5))},
                     {SurfacePoint::at_vertex(VertexId(1)), SurfacePoint::at_vertex(VertexId(2))}, "landmarks", oct.V,
                     oct.F, oct.V, oct.F);
  EXPECT_EQ(vertices.b[1].vertex.idx, 2);
}

TEST(Landmarks, RejectsBadSurfacePointsFromArraysWithTheRow) {
  const TriangleMesh oct = read_mesh(testing::test_data("good/octahedron.off"));
  const SurfacePoint good = SurfacePoint::in_face(FaceId(0), {0.2, 0.3, 0.5});
  const SurfacePoint other = SurfacePoint::in_face(FaceId(5), {0.2, 0.3, 0.5});
  const std::pair<SurfacePoint, const char*> cases[] = {
      {SurfacePoint::in_face(FaceId(8), {0.2, 0.3, 0.5}),
       "landmarks: row 1: face 8 is out of range for mesh B (8 faces)"},
      {SurfacePoint::in_face(FaceId(-1), {0.2, 0.3, 0.5}), "landmarks: row 1: face -1 is out of range for mesh B"},
      {SurfacePoint::in_face(FaceId(1), {0.5, 0.5, 0.5}),
       "landmarks: row 1: barycentric coordinates sum to 1.5, not 1"},
      {SurfacePoint::in_face(FaceId(1), {-0.5, 1, 0.5}), "landmarks: row 1: barycentric coordinate -0.5 is negative"},
      {SurfacePoint::in_face(FaceId(1), {std::nan(""), 0.5, 0.5}), "landmarks: row 1: barycentric coordinate nan is"},
      {SurfacePoint::on_edge(EdgeId(0), 0.5),
       "landmarks: row 1: the landmark on mesh B is not a vertex or a face point"},
      {SurfacePoint::at_vertex(VertexId(6)), "landmarks: row 1: vertex 6 is out of range for mesh B (6 vertices)"},
      {good, "landmarks: row 1: the landmark f0:0.2,0.3,0.5 of mesh B is at the same point as the one of row 0"},
  };
  for (const auto& [second, message] : cases) {
    try {
      make_landmarks({SurfacePoint::at_vertex(VertexId(0)), SurfacePoint::at_vertex(VertexId(1))}, {good, second},
                     "landmarks", oct.V, oct.F, oct.V, oct.F);
      ADD_FAILURE() << message << ": accepted";
    } catch (const InvalidInputError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(make_landmarks({good, other}, {good}, "landmarks", oct.V, oct.F, oct.V, oct.F), InvalidInputError);
  try {
    make_landmarks({good}, {other}, "landmarks", oct.V, oct.F, oct.V, oct.F);
    ADD_FAILURE() << "one pair accepted";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("1 landmark pair(s); at least 2 are needed"), std::string::npos) << e.what();
  }
}

TEST(Landmarks, RejectsBadFilesWithTheLine) {
  const std::pair<const char*, const char*> cases[] = {
      {"bad/lm_out_of_range.txt", "lm_out_of_range.txt:2: vertex 9 is out of range for mesh B"},
      {"bad/lm_duplicate_a.txt", ":2: vertex 0 of mesh A is already a landmark (line 1)"},
      {"bad/lm_three_fields.txt", ":2: expected two landmarks"},
      {"bad/lm_one_pair.txt", "at least 2 are needed"},
      {"bad/lm_surface_point.txt", ":2: 'f3' is a surface point"},
  };
  for (const auto& [file, message] : cases) {
    try {
      read_landmarks(testing::test_data(file), 6, 6);
      ADD_FAILURE() << file << " was accepted";
    } catch (const InvalidInputError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(read_landmarks("/nonexistent/landmarks.txt", 6, 6), IoError);
}

}  // namespace
}  // namespace liftmap
