#include "flatten/flattening_start.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "disk_patches.h"
#include "flatten/distortion.h"
#include "flatten/flattening_checks.h"
#include "flatten/jacobian.h"
#include "flatten/tutte.h"

namespace liftmap {
namespace {

Eigen::MatrixXd unit_circle(size_t n) {
  Eigen::MatrixXd B(static_cast<Eigen::Index>(n), 2);
  for (Eigen::Index i = 0; i < B.rows(); ++i) {
    const double a = 2 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n);
    B.row(i) << std::cos(a), std::sin(a);
  }
  return B;
}

double min_area_ratio(const Eigen::MatrixXi& F, const Eigen::MatrixXd& U) {
  const Eigen::VectorXd a = signed_double_areas(F, U);
  return a.minCoeff() / a.mean();
}

/// The energy joint_flatten chooses starts by: eq. (8) with h = eq. (3), p = 2.
double energy(const testing::TestDisk& d, const Eigen::MatrixXd& U) {
  const JacobianOperator J = jacobian_operator(d.V, d.F);
  return distortion_energy(face_distortion(similarity_parts(J, d.F, U), DistortionCombiner::kNorm), J.area, 2);
}

FlatteningStart start_of(const testing::TestDisk& d) {
  return flattening_start(*d.mesh, d.V, d.boundary, unit_circle(d.boundary.size()),
                          [&](const Eigen::MatrixXd& U) { return energy(d, U); });
}

// The premise: a harmonic start squeezes a capped tube exponentially in its length over girth.
TEST(flatten_start, PlainTutteSqueezesATubeExponentially) {
  const testing::TestDisk short_tube = testing::capped_tube(1);
  const testing::TestDisk long_tube = testing::capped_tube(5);
  const double r1 = min_area_ratio(short_tube.F, tutte_embedding(*short_tube.mesh, short_tube.V, short_tube.boundary,
                                                                 unit_circle(short_tube.boundary.size())));
  const double r5 = min_area_ratio(long_tube.F, tutte_embedding(*long_tube.mesh, long_tube.V, long_tube.boundary,
                                                                unit_circle(long_tube.boundary.size())));
  EXPECT_GT(r1, 1e-8);
  EXPECT_LT(r5, 1e-20) << "plain Tutte no longer squeezes: this test's premise is gone";
}

// The start: every face positive, the boundary where it was asked, and no face below 1e-10 of the mean area for
// tubes whose plain Tutte embedding underflows double precision.
TEST(flatten_start, NoExponentialSqueezeOfAnUncutTube) {
  for (const double lc : {1.0, 3.0, 5.0, 8.0, 12.0, 16.0}) {
    const testing::TestDisk d = testing::capped_tube(lc);
    const FlatteningStart s = start_of(d);
    const Eigen::MatrixXd B = unit_circle(d.boundary.size());
    for (size_t i = 0; i < d.boundary.size(); ++i) {
      ASSERT_EQ(s.U.row(d.boundary[i].idx), B.row(static_cast<Eigen::Index>(i))) << "L/C " << lc;
    }
    const double r = min_area_ratio(d.F, s.U);
    std::printf("L/C %g: %d faces, smallest face %.3g of the mean, drift %g%s, energy %.4g\n", lc,
                static_cast<int>(d.F.rows()), r, s.chosen.drift, s.chosen.local ? " (local)" : "", s.chosen.energy);
    EXPECT_GT(r, 1e-10) << "L/C " << lc;
    EXPECT_DOUBLE_EQ(r, s.chosen.min_area_ratio);
    EXPECT_DOUBLE_EQ(energy(d, s.U), s.chosen.energy);
    // Bijective onto the disk: the flattened areas add up to the polygon's.
    const Eigen::VectorXd a = signed_double_areas(d.F, s.U);
    const double polygon =
        0.5 * static_cast<double>(B.rows()) * std::sin(2 * std::numbers::pi / static_cast<double>(B.rows()));
    EXPECT_NEAR(0.5 * a.sum(), polygon, 1e-9) << "L/C " << lc;
    const Eigen::VectorXd sums = angle_sums(*d.mesh, s.U);
    for (int v = 0; v < d.mesh->n_vertices(); ++v) {
      if (!d.mesh->is_boundary(VertexId(v))) ASSERT_NEAR(sums(v), 2 * std::numbers::pi, 1e-8) << "L/C " << lc;
    }
  }
}

// Where plain Tutte does not squeeze (a patch of a real mesh), the start is no worse than it.
TEST(flatten_start, NoWorseThanPlainTutte) {
  const testing::TestDisk d = testing::mesh_patch("bunny00.off", 0, 2000);
  const FlatteningStart s = start_of(d);
  const Eigen::MatrixXd plain = tutte_embedding(*d.mesh, d.V, d.boundary, unit_circle(d.boundary.size()));
  EXPECT_LE(s.chosen.energy, energy(d, plain));
  ASSERT_FALSE(s.candidates.empty());
  EXPECT_EQ(s.candidates.front().drift, 0);
}

// The drifted embeddings are solved two at a time (one LU per thread): each must be bitwise the one solved alone,
// on one thread or two, so that identical disks still get identical starts.
TEST(flatten_start, DriftedEmbeddingsDoNotDependOnTheThreads) {
  const testing::TestDisk d = testing::capped_tube(5);
  const Eigen::MatrixXd B = unit_circle(d.boundary.size());
  std::vector<double> depth(static_cast<size_t>(d.mesh->n_vertices()));
  for (size_t v = 0; v < depth.size(); ++v) depth[v] = d.V(static_cast<Eigen::Index>(v), 2);
  std::vector<TutteWeights> sets;
  for (const double drift : {0.0, 0.5, 1.0, 2.0, 3.0}) sets.push_back({.depth = depth, .drift = drift});
  const int threads = omp_get_max_threads();
  std::vector<std::vector<Eigen::MatrixXd>> runs;
  for (const int t : {1, 2}) {
    omp_set_num_threads(t);
    runs.push_back(tutte_embeddings(*d.mesh, d.V, d.boundary, B, sets));
  }
  omp_set_num_threads(threads);
  for (size_t s = 0; s < sets.size(); ++s) {
    const Eigen::MatrixXd alone = tutte_embedding(*d.mesh, d.V, d.boundary, B, sets[s]);
    EXPECT_TRUE(runs[0][s] == alone) << "set " << s << " on one thread";
    EXPECT_TRUE(runs[1][s] == alone) << "set " << s << " on two threads";
    if (s > 0) {
      EXPECT_FALSE(alone == runs[0][0]) << "the drift " << sets[s].drift << " changed nothing";
    }
  }
}

}  // namespace
}  // namespace liftmap
