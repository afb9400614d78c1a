#include "render/alignment.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "common/test_meshes.h"
#include "core/errors.h"

namespace liftmap {
namespace {

TEST(RenderAlignSimilarity, RecoversKnownTransform) {
  const Eigen::MatrixXd P = Eigen::MatrixXd::Random(9, 3);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(2.1, Eigen::Vector3d(0.3, -1.0, 0.5).normalized()).toRotationMatrix();
  const double scale = 0.37;
  const Eigen::Vector3d t(4.0, -2.5, 7.0);
  // Q = R^T (P - t) / scale, so that scale R Q + t = P.
  const Eigen::MatrixXd Q = ((P.rowwise() - t.transpose()) * R / scale).eval();
  const SimilarityTransform s = align_similarity(P, Q);
  EXPECT_LT((s.R - R).norm(), 1e-9);
  EXPECT_NEAR(s.scale, scale, 1e-9);
  EXPECT_LT((s.t - t).norm(), 1e-9);
  EXPECT_NEAR(s.R.determinant(), 1.0, 1e-12);
  EXPECT_LT((s.apply(Q) - P).norm(), 1e-9);
}

TEST(RenderAlignSimilarity, NeverReflects) {
  // Mirror images: the best proper rotation, not the reflection.
  const Eigen::MatrixXd P = Eigen::MatrixXd::Random(12, 3);
  Eigen::MatrixXd Q = P;
  Q.col(2) *= -1.0;
  const SimilarityTransform s = align_similarity(P, Q);
  EXPECT_NEAR(s.R.determinant(), 1.0, 1e-12);
  EXPECT_LT((s.R * s.R.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_GT(s.scale, 0.0);
}

TEST(RenderAlignSimilarity, TwoPointsAreMatchedExactly) {
  // Any two distinct points map onto any two others; the rotation about their line is free.
  const Eigen::MatrixXd P = (Eigen::MatrixXd(2, 3) << 1, 2, 3, -1, 0, 2).finished();
  const Eigen::MatrixXd Q = (Eigen::MatrixXd(2, 3) << 0, 0, 0, 0, 4, 0).finished();
  const SimilarityTransform s = align_similarity(P, Q);
  EXPECT_NEAR(s.R.determinant(), 1.0, 1e-12);
  EXPECT_LT((s.R * s.R.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_NEAR(s.scale, 3.0 / 4.0, 1e-12);  // |P_0 - P_1| = 3, |Q_0 - Q_1| = 4
  EXPECT_LT((s.apply(Q) - P).norm(), 1e-12);
}

TEST(RenderAlignSimilarity, CoincidentTargetsGiveScaleZero) {
  // Every source point best maps onto the one target point: scale 0, R the identity, t that point.
  const Eigen::MatrixXd Q = Eigen::MatrixXd::Random(4, 3);
  const Eigen::MatrixXd P = Eigen::RowVector3d(1.0, -2.0, 0.5).replicate(4, 1);
  const SimilarityTransform s = align_similarity(P, Q);
  EXPECT_EQ(s.scale, 0.0);
  EXPECT_TRUE(s.R.isIdentity(0.0));
  EXPECT_LT((s.t - Eigen::Vector3d(1.0, -2.0, 0.5)).norm(), 1e-12);
  EXPECT_LT((s.apply(Q) - P).norm(), 1e-12);
}

TEST(RenderAlignSimilarity, RejectsBadInput) {
  EXPECT_THROW(align_similarity(Eigen::MatrixXd::Zero(3, 3), Eigen::MatrixXd::Zero(2, 3)), InvalidInputError);
  EXPECT_THROW(align_similarity(Eigen::MatrixXd::Zero(1, 3), Eigen::MatrixXd::Zero(1, 3)), InvalidInputError);
  EXPECT_THROW(align_similarity(Eigen::MatrixXd::Random(3, 3), Eigen::MatrixXd::Ones(3, 3)), InvalidInputError);
}

TEST(RenderDefaultView, OrthonormalThreeQuarterViewFromTheLandmarksSide) {
  // A flat box, thinnest along z, landmarks on its +z face: the eye is on +z, turned away from the axis.
  Eigen::MatrixXd V = Eigen::MatrixXd::Random(500, 3);
  V.col(0) *= 3.0;
  V.col(1) *= 2.0;
  V.col(2) *= 0.5;
  const Eigen::MatrixXd L = (Eigen::MatrixXd(2, 3) << 1, 0, 0.5, -1, 1, 0.5).finished();
  const ViewDirection view = default_view(V, L);
  EXPECT_NEAR(view.direction.norm(), 1.0, 1e-12);
  EXPECT_NEAR(view.up.norm(), 1.0, 1e-12);
  EXPECT_NEAR(view.direction.dot(view.up), 0.0, 1e-12);
  EXPECT_LT(view.direction.z(), -0.7);   // looking toward -z, from the landmarks' side
  EXPECT_GT(view.direction.z(), -0.95);  // but not straight on
  EXPECT_GT(view.up.y(), 0.9);           // world +y is up
  EXPECT_LT(view.direction.y(), 0.0);    // from slightly above
}

TEST(RenderDefaultView, RealMeshes) {
  for (const char* name : {"camel.off", "cow.off", "hand.off"}) {
    const TriangleMesh mesh = testing::read_demo_mesh(name);
    ASSERT_GT(mesh.V.rows(), 0);
    const ViewDirection view = default_view(mesh.V, mesh.V.topRows(3));
    EXPECT_NEAR(view.direction.norm(), 1.0, 1e-12) << name;
    EXPECT_NEAR(view.direction.dot(view.up), 0.0, 1e-12) << name;
  }
}

}  // namespace
}  // namespace liftmap
