// The second-order cone's algebra against its direct formulas: dense matrices J, W = beta (2 v v^T - J), and
// det(x + a d) evaluated from its definition.
#include "flatten/second_order_cone.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>

namespace liftmap {
namespace {

constexpr double kTol = 1e-12;

Eigen::MatrixXd jordan_j(Eigen::Index n) {
  Eigen::MatrixXd J = -Eigen::MatrixXd::Identity(n, n);
  J(0, 0) = 1;
  return J;
}

// A random point of the cone's interior: x0 = |x1| (1 + margin) + small.
Eigen::VectorXd interior_point(std::mt19937& rng, Eigen::Index n, double margin) {
  std::normal_distribution<double> normal;
  Eigen::VectorXd x(n);
  for (Eigen::Index i = 1; i < n; ++i) x(i) = normal(rng);
  x(0) = x.tail(n - 1).norm() * (1 + margin) + 1e-3;
  return x;
}

Eigen::VectorXd random_vector(std::mt19937& rng, Eigen::Index n) {
  std::normal_distribution<double> normal;
  Eigen::VectorXd x(n);
  for (Eigen::Index i = 0; i < n; ++i) x(i) = normal(rng);
  return x;
}

double direct_det(const Eigen::VectorXd& x) { return x.dot(jordan_j(x.size()) * x); }

class flatten_second_order_cone : public ::testing::TestWithParam<int> {};

TEST_P(flatten_second_order_cone, DeterminantAndInteriorMatchTheirDefinitions) {
  std::mt19937 rng(1);
  const int n = GetParam();
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::VectorXd x = random_vector(rng, n);
    EXPECT_NEAR(soc::det(x), direct_det(x), kTol * x.squaredNorm());
    EXPECT_EQ(soc::interior(x), x(0) > x.tail(n - 1).norm());
  }
  Eigen::VectorXd boundary = Eigen::VectorXd::Zero(n);
  boundary(0) = boundary(1) = 1;
  EXPECT_FALSE(soc::interior(boundary));
  EXPECT_EQ(soc::det(boundary), 0);
}

TEST_P(flatten_second_order_cone, JordanProductDivisionAndInverse) {
  std::mt19937 rng(2);
  const int n = GetParam();
  Eigen::VectorXd e = Eigen::VectorXd::Zero(n);
  e(0) = 1;
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::VectorXd x = random_vector(rng, n), y = random_vector(rng, n);
    const Eigen::VectorXd p = soc::jordan_product<Eigen::Dynamic>(x, y);
    // x o y = (x^T y, x0 y1 + y0 x1), commutative, with e as unit.
    EXPECT_NEAR(p(0), x.dot(y), kTol * x.norm() * y.norm());
    EXPECT_LE((p.tail(n - 1) - (x(0) * y.tail(n - 1) + y(0) * x.tail(n - 1))).norm(), kTol * x.norm() * y.norm());
    EXPECT_LE((p - soc::jordan_product<Eigen::Dynamic>(y, x)).norm(), kTol * p.norm());
    EXPECT_LE((soc::jordan_product<Eigen::Dynamic>(e, x) - x).norm(), kTol * x.norm());

    const Eigen::VectorXd lambda = interior_point(rng, n, 0.1);
    const Eigen::VectorXd u = soc::jordan_divide<Eigen::Dynamic>(lambda, y);
    EXPECT_LE((soc::jordan_product<Eigen::Dynamic>(lambda, u) - y).norm(), 1e-10 * y.norm() * (1 + u.norm()));
    const Eigen::VectorXd inv = soc::inverse(lambda);
    EXPECT_LE((soc::jordan_product<Eigen::Dynamic>(lambda, inv) - e).norm(), 1e-10 * (1 + inv.norm()));
  }
  EXPECT_DOUBLE_EQ(soc::inverse(Eigen::VectorXd::Constant(1, 4))(0), 0.25);
}

// W = beta (2 v v^T - J) with W z = W^-1 s = lambda (the Nesterov-Todd point), det wbar = 1, and the documented
// W^-2 = (2 J wbar (J wbar)^T - J) / beta^2.
TEST_P(flatten_second_order_cone, NesterovToddScalingMapsZAndSToTheSamePoint) {
  std::mt19937 rng(3);
  const int n = GetParam();
  const Eigen::MatrixXd J = jordan_j(n);
  for (int trial = 0; trial < 50; ++trial) {
    // Near the boundary too: margins from 1e-6 to 10.
    const double margin = std::pow(10.0, -6 + trial % 7);
    const Eigen::VectorXd s = interior_point(rng, n, margin), z = interior_point(rng, n, 1.0);
    const soc::Scaling<Eigen::Dynamic> w = soc::nesterov_todd<Eigen::Dynamic>(s, z);
    const Eigen::MatrixXd W = w.beta * (2 * w.v * w.v.transpose() - J);
    const Eigen::MatrixXd Winv = W.inverse();
    const Eigen::VectorXd lambda = W * z;
    EXPECT_LE((Winv * s - lambda).norm(), 1e-9 * lambda.norm()) << "margin " << margin;
    EXPECT_NEAR(soc::det(w.wbar), 1, 1e-9);
    EXPECT_NEAR(w.beta, std::pow(direct_det(s) / direct_det(z), 0.25), 1e-9 * w.beta);
    const Eigen::VectorXd jw = J * w.wbar;
    const Eigen::MatrixXd Wm2 = (2 * jw * jw.transpose() - J) / (w.beta * w.beta);
    EXPECT_LE((Wm2 - Winv * Winv).norm(), 1e-8 * Wm2.norm()) << "margin " << margin;
    const Eigen::VectorXd x = random_vector(rng, n);
    EXPECT_LE((soc::apply_w<Eigen::Dynamic>(w, x) - W * x).norm(), kTol * W.norm() * x.norm());
    EXPECT_LE((soc::apply_w_inverse<Eigen::Dynamic>(w, x) - Winv * x).norm(), 1e-10 * Winv.norm() * x.norm());
  }
}

// The step to the boundary: det(x + a d) = 0 at a, inside just before, outside just after; +infinity along rays
// that stay inside.
TEST_P(flatten_second_order_cone, MaxStepEndsOnTheBoundary) {
  std::mt19937 rng(4);
  const int n = GetParam();
  int finite = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::VectorXd x = interior_point(rng, n, 0.5), d = random_vector(rng, n);
    const double a = soc::max_step<Eigen::Dynamic>(x, d);
    ASSERT_GT(a, 0);
    if (!std::isfinite(a)) {
      for (const double t : {1.0, 10.0, 1e3, 1e6}) EXPECT_TRUE(soc::interior(Eigen::VectorXd(x + t * d))) << t;
      continue;
    }
    ++finite;
    const Eigen::VectorXd at = x + a * d;
    EXPECT_NEAR(direct_det(at), 0, 1e-9 * at.squaredNorm());
    EXPECT_GE(at(0), -1e-12 * at.norm()) << "the root is on the cone, not on its negative";
    EXPECT_TRUE(soc::interior(Eigen::VectorXd(x + 0.999 * a * d)));
    EXPECT_FALSE(soc::interior(Eigen::VectorXd(x + 1.001 * a * d)));
  }
  EXPECT_GT(finite, 50);
  Eigen::VectorXd inside = Eigen::VectorXd::Zero(n);
  inside(0) = 1;
  EXPECT_EQ(soc::max_step<Eigen::Dynamic>(inside, inside), std::numeric_limits<double>::infinity());
  EXPECT_DOUBLE_EQ(soc::max_step_linear(2, -4), 0.5);
  EXPECT_EQ(soc::max_step_linear(2, 1), std::numeric_limits<double>::infinity());
}

// The fixed-size instantiation the solver uses for its faces' cones agrees with the dynamic one.
TEST(flatten_second_order_cone_fixed, ThreeDimensionalConesAgreeWithTheDynamicForm) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d s = interior_point(rng, 3, 0.01), z = interior_point(rng, 3, 1.0);
    const Eigen::Vector3d x = random_vector(rng, 3);
    const soc::Scaling<3> w3 = soc::nesterov_todd<3>(s, z);
    const soc::Scaling<Eigen::Dynamic> wd = soc::nesterov_todd<Eigen::Dynamic>(s, z);
    EXPECT_LE((soc::apply_w<3>(w3, x) - soc::apply_w<Eigen::Dynamic>(wd, x)).norm(), 1e-14 * x.norm() * w3.beta);
    EXPECT_LE((soc::jordan_divide<3>(s, x) - soc::jordan_divide<Eigen::Dynamic>(s, x)).norm(), 1e-12 * x.norm());
    EXPECT_EQ(soc::max_step<3>(s, x), soc::max_step<Eigen::Dynamic>(s, x));
  }
}

INSTANTIATE_TEST_SUITE_P(Dimensions, flatten_second_order_cone, ::testing::Values(2, 3, 8));

}  // namespace
}  // namespace liftmap
