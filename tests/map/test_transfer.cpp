#include "map/transfer.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>

#include "common/test_meshes.h"
#include "core/errors.h"
#include "map/write_map.h"

namespace liftmap {
namespace {

// The identity map of a mesh: every vertex at the first face that uses it.
std::vector<SurfacePoint> identity_map(const TriangleMesh& m) {
  std::vector<SurfacePoint> map(static_cast<size_t>(m.V.rows()));
  for (Eigen::Index f = m.F.rows() - 1; f >= 0; --f) {
    for (int k = 0; k < 3; ++k) {
      std::array<double, 3> b{0, 0, 0};
      b[static_cast<size_t>(k)] = 1;
      map[static_cast<size_t>(m.F(f, k))] = SurfacePoint::in_face(FaceId(static_cast<int>(f)), b);
    }
  }
  return map;
}

TEST(Transfer, EvalOfAMapAgainstItselfIsZeroAndAgainstAPerturbedCopyIsThePerturbation) {
  const TriangleMesh m = testing::read_demo_mesh("ellipsoid.off");
  const auto map = identity_map(m);
  const MapDifference same = compare_maps(m.V, m.F, map, map);
  EXPECT_EQ(same.mean, 0.0);
  EXPECT_EQ(same.max, 0.0);

  double area = 0;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  // Move vertex 7's image 10% of the way toward the next corner of its face.
  auto moved = map;
  SurfacePoint& p = moved[7];
  int k = 0;
  while (p.bary[static_cast<size_t>(k)] != 1.0) ++k;
  const int next = (k + 1) % 3;
  p.bary[static_cast<size_t>(k)] = 0.9;
  p.bary[static_cast<size_t>(next)] = 0.1;
  const double expected = 0.1 * (m.V.row(m.F(p.face.idx, next)) - m.V.row(7)).norm() / std::sqrt(area);
  const MapDifference d = compare_maps(m.V, m.F, moved, map);
  EXPECT_NEAR(d.max, expected, 1e-15);
  EXPECT_NEAR(d.mean, expected / static_cast<double>(m.V.rows()), 1e-15);
  EXPECT_EQ(d.worst_vertex, 7);
  EXPECT_THROW(compare_maps(m.V, m.F, moved, std::vector<SurfacePoint>(3)), InvalidInputError);
}

TEST(Transfer, FoldedFacesOfAPlacedMesh) {
  const TriangleMesh m = testing::read_demo_mesh("ellipsoid.off");
  auto map = identity_map(m);
  EXPECT_TRUE(folded_faces(m.F, interpolate_at(m.F, m.V, map), m.V, m.F, map).empty());
  // Reversed faces are all folded against the surface.
  Eigen::MatrixXi reversed = m.F;
  reversed.col(1).swap(reversed.col(2));
  EXPECT_EQ(folded_faces(reversed, interpolate_at(m.F, m.V, map), m.V, m.F, map).size(),
            static_cast<size_t>(m.F.rows()));
  // Vertex 0's image moved across its fan to the far side of a neighbour: the faces around it fold over.
  const int v = m.F(0, 0), w = m.F(0, 1);
  std::vector<int> around;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    if ((m.F.row(f).array() == v).any()) around.push_back(static_cast<int>(f));
  }
  const Eigen::Vector3d target = 2 * Eigen::Vector3d(m.V.row(w)) - Eigen::Vector3d(m.V.row(v));
  Eigen::MatrixXd placed = interpolate_at(m.F, m.V, map);
  placed.row(v) = target.transpose();
  const auto folded = folded_faces(m.F, placed, m.V, m.F, map);
  EXPECT_FALSE(folded.empty());
  for (const int f : folded) EXPECT_TRUE(std::find(around.begin(), around.end(), f) != around.end()) << f;
}

TEST(Transfer, AttributesInterpolateAtMapPointsAndRoundTripThroughFiles) {
  const TriangleMesh m = testing::read_demo_mesh("ellipsoid.off");
  const auto map = identity_map(m);
  // Transferring positions through the identity map gives the positions back.
  EXPECT_LT((interpolate_at(m.F, m.V, map) - m.V).norm(), 1e-15);
  const std::string path = (std::filesystem::temp_directory_path() / "liftmap_test_attributes.txt").string();
  write_attributes(path, m.V);
  EXPECT_EQ(read_attributes(path), m.V);
  write_vertex_map(path, map, "identity");
  const auto back = read_vertex_map(path, static_cast<int>(m.F.rows()));
  ASSERT_EQ(back.size(), map.size());
  for (size_t i = 0; i < map.size(); ++i) EXPECT_EQ(back[i].face, map[i].face);
  EXPECT_THROW(read_vertex_map(path, 2), IoError);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace liftmap
