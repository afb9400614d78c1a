#include "io/vertex_map.h"

#include <gtest/gtest.h>

#include <sstream>

#include "core/errors.h"

namespace liftmap {
namespace {

std::vector<SurfacePoint> read(const std::string& text, int n_faces = 10) {
  std::istringstream in(text);
  return read_vertex_map(in, "m.txt", n_faces);
}

template <class Error>
std::string error_of(const std::string& text) {
  try {
    read(text);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error of the expected type";
}

TEST(ReadVertexMap, ReadsFacePointsWithCommentsAndAByteOrderMark) {
  const auto p = read("\xEF\xBB\xBF# header\n3 0.25 0.25 0.5\n\n9 1 0 0  # comment\n");
  ASSERT_EQ(p.size(), 2U);
  EXPECT_EQ(p[0].face.idx, 3);
  EXPECT_EQ(p[0].bary[2], 0.5);
  EXPECT_EQ(p[1].face.idx, 9);
}

TEST(ReadVertexMap, AcceptsRoundingWithinTheTolerance) {
  EXPECT_EQ(read("0 0.3333333 0.3333333 0.3333334\n1 -1e-7 0.5 0.5000001\n").size(), 2U);
}

TEST(ReadVertexMap, RejectsPointsThatAreNotOnTheirFaceWithTheLine) {
  // Values that eval turned into "mean error: nan" and transfer into NaN or off-surface points.
  EXPECT_EQ(error_of<InvalidInputError>("0 1 0 0\n0 nan 0.5 0.5\n"),
            "m.txt:2: barycentric coordinate nan is not finite");
  EXPECT_EQ(error_of<InvalidInputError>("0 -0.5 1 0.5\n"),
            "m.txt:1: barycentric coordinate -0.5 is negative: the point is outside face 0");
  EXPECT_EQ(error_of<InvalidInputError>("0 0.5 0.5 0.5\n"),
            "m.txt:1: barycentric coordinates sum to 1.5, not 1 (tolerance 1e-06)");
  EXPECT_EQ(error_of<InvalidInputError>("0 1e308 0 0\n"),
            "m.txt:1: barycentric coordinates sum to 1e+308, not 1 (tolerance 1e-06)");
  EXPECT_EQ(error_of<InvalidInputError>("0 1e400 0 0\n"), "m.txt:1: barycentric coordinate 1e400 is not finite");
}

TEST(ReadVertexMap, RejectsMalformedLinesWithTheLine) {
  EXPECT_EQ(error_of<IoError>("0 1 0 0\n\n10 1 0 0\n"),
            "m.txt:3: face 10 is not a face index of the target mesh (10 faces)");
  EXPECT_EQ(error_of<IoError>("-1 1 0 0\n"), "m.txt:1: face -1 is not a face index of the target mesh (10 faces)");
  EXPECT_EQ(error_of<IoError>("2.5 1 0 0\n"), "m.txt:1: face 2.5 is not a face index of the target mesh (10 faces)");
  EXPECT_EQ(error_of<IoError>("0 1 0\n"), "m.txt:1: expected 'face b0 b1 b2', found 3 fields");
  EXPECT_EQ(error_of<IoError>("0 one 0 0\n"), "m.txt:1: 'one' is not a number");
  EXPECT_EQ(error_of<IoError>("# nothing\n"), "m.txt: no map lines ('face b0 b1 b2')");
}

TEST(ReadVertexMap, WriteReadRoundTripIsExact) {
  const std::string path = ::testing::TempDir() + "liftmap_test_map.txt";
  const std::vector<SurfacePoint> p = {SurfacePoint::in_face(FaceId(4), {0.1, 0.2, 0.7}),
                                       SurfacePoint::in_face(FaceId(0), {1.0 / 3, 1.0 / 3, 1.0 / 3})};
  write_vertex_map(path, p, "test");
  const auto q = read_vertex_map(path, 5);
  ASSERT_EQ(q.size(), 2U);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(q[i].face.idx, p[i].face.idx);
    EXPECT_EQ(q[i].bary, p[i].bary);
  }
  EXPECT_THROW(read_vertex_map(path, 4), IoError) << "face 4 is out of range for 4 faces";
}

}  // namespace
}  // namespace liftmap
