#include "core/surface_point.h"

#include <gtest/gtest.h>

#include <random>

#include "common/test_meshes.h"

namespace liftmap {
namespace {

TEST(SurfacePoint, EveryKindInterpolatesTheSamePositionAsItsFacePoint) {
  const TriangleMesh tm = testing::read_demo_mesh("cow.off");
  const Mesh m(tm.F, static_cast<int>(tm.V.rows()));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 500; ++i) {
    const VertexId v(static_cast<int>(rng() % static_cast<unsigned>(m.n_vertices())));
    const EdgeId e(static_cast<int>(rng() % static_cast<unsigned>(m.n_edges())));
    const FaceId f(static_cast<int>(rng() % static_cast<unsigned>(m.n_faces())));
    const double a = u(rng), b = u(rng) * (1 - a);
    for (const SurfacePoint& p :
         {SurfacePoint::at_vertex(v), SurfacePoint::on_edge(e, u(rng)), SurfacePoint::in_face(f, {a, b, 1 - a - b})}) {
      const SurfacePoint q = as_face_point(m, p);
      ASSERT_EQ(q.kind, SurfacePoint::Kind::kFace);
      EXPECT_NEAR(q.bary[0] + q.bary[1] + q.bary[2], 1.0, 1e-15);
      EXPECT_LT((interpolate(m, tm.V, p) - interpolate(m, tm.V, q)).norm(), 1e-12);
    }
  }
}

TEST(SurfacePoint, EdgeParameterRunsFromTailToHead) {
  Eigen::MatrixXi F(2, 3);
  F << 0, 1, 2, 2, 1, 3;
  Eigen::MatrixXd V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0;
  const Mesh m(F, 4);
  for (int e = 0; e < m.n_edges(); ++e) {
    const HalfedgeId h = Mesh::halfedge(EdgeId(e));
    const Eigen::RowVectorXd p = interpolate(m, V, SurfacePoint::on_edge(EdgeId(e), 0.25));
    EXPECT_LT((p - (0.75 * V.row(m.tail(h).idx) + 0.25 * V.row(m.head(h).idx))).norm(), 1e-15);
  }
}

}  // namespace
}  // namespace liftmap
