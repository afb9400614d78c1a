#include "flatten/tutte.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "core/errors.h"
#include "disk_patches.h"
#include "flatten/flattening_checks.h"

namespace liftmap {
namespace {

struct Case {
  const char* mesh;
  int seed;
  int faces;
};

class flatten_tutte : public ::testing::TestWithParam<Case> {};

TEST_P(flatten_tutte, BijectiveOntoConvexPolygon) {
  const Case c = GetParam();
  const testing::TestDisk d = testing::mesh_patch(c.mesh, c.seed, c.faces);
  const auto nb = static_cast<Eigen::Index>(d.boundary.size());
  Eigen::MatrixXd B(nb, 2);
  for (Eigen::Index i = 0; i < nb; ++i) {
    const double a = 2 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(nb);
    B.row(i) << std::cos(a), std::sin(a);
  }
  const Eigen::MatrixXd U = tutte_embedding(*d.mesh, d.V, d.boundary, B);
  ASSERT_EQ(U.rows(), d.V.rows());
  for (Eigen::Index i = 0; i < nb; ++i) {
    EXPECT_EQ(U.row(d.boundary[static_cast<size_t>(i)].idx), B.row(i)) << "boundary vertex " << i;
  }
  const Eigen::VectorXd a = signed_double_areas(d.F, U);
  EXPECT_GT(a.minCoeff(), 0) << c.mesh << ": flipped or degenerate face";
  // Bijective onto the polygon: the flattened areas add up to the polygon's area, and angle sums are 2 pi inside.
  const double polygon = 0.5 * nb * std::sin(2 * std::numbers::pi / static_cast<double>(nb));
  EXPECT_NEAR(0.5 * a.sum(), polygon, 1e-9);
  const Eigen::VectorXd sums = angle_sums(*d.mesh, U);
  for (int v = 0; v < d.mesh->n_vertices(); ++v) {
    if (!d.mesh->is_boundary(VertexId(v))) EXPECT_NEAR(sums(v), 2 * std::numbers::pi, 1e-9) << "vertex " << v;
  }
}

INSTANTIATE_TEST_SUITE_P(RealPatches, flatten_tutte,
                         ::testing::Values(Case{"camel.off", 0, 800}, Case{"cow.off", 100, 1500},
                                           Case{"bull.off", 7, 3000}, Case{"dino.off", 50, 500},
                                           Case{"man.off", 1000, 2000}),
                         [](const auto& info) {
                           std::string name = info.param.mesh;
                           return name.substr(0, name.find('.'));
                         });

TEST(flatten_tutte, RejectsWrongBoundarySize) {
  const testing::TestDisk d = testing::mesh_patch("cow.off", 0, 100);
  EXPECT_THROW(tutte_embedding(*d.mesh, d.V, d.boundary, Eigen::MatrixXd::Zero(3, 2)), InvalidInputError);
}

}  // namespace
}  // namespace liftmap
