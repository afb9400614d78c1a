#include "flatten/jacobian.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "disk_patches.h"
#include "flatten/distortion.h"

namespace liftmap {
namespace {

// A flattening that is an affine map of a planar patch has that map's Jacobian on every face, and the 2-vector
// singular values agree with an SVD.
TEST(flatten_jacobian, AffineMapOfPlanarPatchAndSingularValues) {
  const testing::TestDisk d = testing::mesh_patch("cow.off", 10, 300);
  Eigen::MatrixXd V = Eigen::MatrixXd::Zero(d.V.rows(), 3);
  V.leftCols(2) = d.V.leftCols(2);  // planar rest shape: the local frame is the xy plane up to a rotation
  Eigen::Matrix2d A;
  A << 1.3, -0.4, 0.7, 0.9;
  const Eigen::MatrixXd U = V.leftCols(2) * A.transpose();
  const Eigen::MatrixXi F = d.F;
  // Drop faces that are degenerate after the projection.
  const JacobianOperator op = jacobian_operator(V, F);
  const Eigen::MatrixXd P = similarity_parts(op, F, U);
  const Eigen::MatrixXd S = singular_values(P);
  const Eigen::Vector2d sv = Eigen::JacobiSVD<Eigen::Matrix2d>(A).singularValues();
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    // Frames differ from the xy frame by a rotation (or a reflection for faces seen from below), which keeps
    // the singular values.
    EXPECT_NEAR(S(f, 0), sv(0), 1e-8) << "face " << f;
    EXPECT_NEAR(S(f, 1), sv(1), 1e-8) << "face " << f;
  }
}

TEST(flatten_distortion, ConvexifiedSigmaIsALowerBoundTightAtThePolarRotation) {
  Eigen::MatrixXd P(3, 4);
  P << 1.2, 0.3, 0.2, -0.1,  //
      0.5, -0.9, 0.3, 0.3,   //
      2.0, 0.0, 0.0, 0.0;
  const Eigen::VectorXd theta = polar_rotations(P);
  const Eigen::MatrixXd S = singular_values(P);
  const Eigen::VectorXd tight = convexified_sigma(P, theta);
  for (Eigen::Index f = 0; f < P.rows(); ++f) {
    EXPECT_NEAR(tight(f), S(f, 1), 1e-12);
    for (const double d : {-0.5, 0.1, 1.0}) {
      Eigen::VectorXd other = theta;
      other(f) += d;
      EXPECT_LT(convexified_sigma(P, other)(f), S(f, 1));
    }
  }
  EXPECT_EQ(face_distortion(P, DistortionCombiner::kMax)(2), 2.0);
  EXPECT_NEAR(distortion_energy(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(1, 1, 2), 2), std::sqrt(1 + 4 + 18), 1e-12);
}

}  // namespace
}  // namespace liftmap
