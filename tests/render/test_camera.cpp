#include "render/camera.h"

#include <gtest/gtest.h>

#include "common/test_meshes.h"
#include "core/errors.h"

namespace liftmap {
namespace {

TEST(RenderCamera, ProjectsTargetToCentre) {
  Camera camera;
  camera.eye = Eigen::Vector3d(0, 0, 5);
  const ProjectedPoint q = project(camera, 2.0, Eigen::Vector3d::Zero());
  EXPECT_NEAR(q.ndc.norm(), 0.0, 1e-12);
  EXPECT_NEAR(q.depth, 5.0, 1e-12);
  // Right and up in the world are right and up in the image.
  EXPECT_GT(project(camera, 2.0, Eigen::Vector3d(1, 0, 0)).ndc.x(), 0);
  EXPECT_GT(project(camera, 2.0, Eigen::Vector3d(0, 1, 0)).ndc.y(), 0);
}

TEST(RenderCamera, FitFramesEveryVertex) {
  const TriangleMesh mesh = testing::read_demo_mesh("camel.off");
  ASSERT_GT(mesh.V.rows(), 0);
  for (const Projection projection : {Projection::kOrthographic, Projection::kPerspective}) {
    const double aspect = 1.5;
    const Camera camera =
        fit_camera(mesh.V, Eigen::Vector3d(1, -0.3, 0.2), Eigen::Vector3d(0, 1, 0), aspect, projection, 0.8);
    Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e9), hi = -lo;
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
      const ProjectedPoint q = project(camera, aspect, mesh.V.row(i).transpose());
      EXPECT_GT(q.depth, 0);
      lo = lo.cwiseMin(q.ndc);
      hi = hi.cwiseMax(q.ndc);
    }
    // Centred, and the larger relative extent is the requested fill.
    EXPECT_NEAR(lo.x() + hi.x(), 0.0, 0.02);
    EXPECT_NEAR(lo.y() + hi.y(), 0.0, 0.02);
    EXPECT_NEAR(std::max(hi.x() - lo.x(), hi.y() - lo.y()) / 2, 0.8, 0.02);
  }
}

TEST(RenderCamera, RejectsBadInput) {
  EXPECT_THROW(bounding_sphere(Eigen::MatrixXd()), InvalidInputError);
  const Eigen::MatrixXd V = Eigen::MatrixXd::Random(5, 3);
  EXPECT_THROW(fit_camera(V, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY(), 1.0), InvalidInputError);
  EXPECT_THROW(fit_camera(V, Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitY(), 1.0), InvalidInputError);
}

}  // namespace
}  // namespace liftmap
