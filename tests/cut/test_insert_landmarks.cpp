#include "cut/insert_landmarks.h"

#include <gtest/gtest.h>

#include "core/errors.h"
#include "cut_test_util.h"

namespace liftmap {
namespace {

// Points inside faces (two in one face), on edges (two on one edge) and at vertices become refined vertices at
// exactly their points; the input vertices keep their ids and the refined mesh is still the input surface.
TEST(insert_landmarks, EveryKindOfPointBecomesAVertexAtItsPoint) {
  for (const char* name : {"cow", "hand", "bull"}) {
    SCOPED_TRACE(name);
    const auto m = test::load(name);
    const Mesh input(m.F, static_cast<int>(m.V.rows()));
    const double scale = (m.V.colwise().maxCoeff() - m.V.colwise().minCoeff()).norm();
    const EdgeId e(11);
    const std::vector<SurfacePoint> points{
        SurfacePoint::in_face(FaceId(3), {0.2, 0.3, 0.5}),
        SurfacePoint::in_face(FaceId(3), {0.6, 0.3, 0.1}),
        SurfacePoint::on_edge(e, 0.25),
        SurfacePoint::on_edge(e, 0.75),
        SurfacePoint::in_face(FaceId(40), {0, 0.5, 0.5}),  // on a side of face 40
        SurfacePoint::in_face(FaceId(41), {0, 1, 0}),      // a corner of face 41
        SurfacePoint::at_vertex(VertexId(100)),
    };
    RefinedMesh r = make_refined_mesh(input, m.V);
    const std::vector<int> ids = insert_landmarks(r, input, points);
    ASSERT_EQ(ids.size(), points.size());
    EXPECT_EQ(r.n_vertices(), input.n_vertices() + 5);
    EXPECT_EQ(ids[5], m.F(41, 1));
    EXPECT_EQ(ids[6], 100);
    const Eigen::MatrixXd V = r.vertex_matrix();
    EXPECT_EQ(V.topRows(m.V.rows()), m.V);
    for (size_t i = 0; i < points.size(); ++i) {
      EXPECT_LT((V.row(ids[i]) - interpolate(input, m.V, points[i])).norm(), 1e-12 * scale) << i;
    }
    EXPECT_TRUE(r.mesh.boundary_loops().empty());
    EXPECT_EQ(r.mesh.euler_characteristic(), 2);
    EXPECT_NEAR(test::area(V, r.face_matrix()), test::area(m.V, m.F), 1e-12 * test::area(m.V, m.F));
  }
}

TEST(insert_landmarks, VertexLandmarksLeaveTheMeshAsItIs) {
  const auto m = test::load("cow");
  const Mesh input(m.F, static_cast<int>(m.V.rows()));
  RefinedMesh r = make_refined_mesh(input, m.V);
  const auto ids =
      insert_landmarks(r, input, {SurfacePoint::at_vertex(VertexId(5)), SurfacePoint::at_vertex(VertexId(9))});
  EXPECT_EQ(ids, (std::vector<int>{5, 9}));
  EXPECT_EQ(r.face_matrix(), m.F);
}

TEST(insert_landmarks, APointAtAnotherLandmarksPlaceIsRejected) {
  const auto m = test::load("cow");
  const Mesh input(m.F, static_cast<int>(m.V.rows()));
  RefinedMesh r = make_refined_mesh(input, m.V);
  const std::vector<SurfacePoint> twice{SurfacePoint::in_face(FaceId(3), {0.2, 0.3, 0.5}),
                                        SurfacePoint::in_face(FaceId(3), {0.2, 0.3, 0.5})};
  EXPECT_THROW(insert_landmarks(r, input, twice), InvalidInputError);
}

}  // namespace
}  // namespace liftmap
