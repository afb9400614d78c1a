#include "cut/boundary_correspondence.h"

#include <gtest/gtest.h>

namespace liftmap {
namespace {

TEST(cut_boundary_correspondence, CubicHasUnitSpeedAtEndsAndIsMonotone) {
  for (const auto& [l, L] : {std::pair{1.0, 1.0}, std::pair{1.0, 1.5}, std::pair{2.0, 7.0}, std::pair{0.3, 0.31}}) {
    EXPECT_DOUBLE_EQ(cubic_reparameterisation(0, l, L), 0);
    EXPECT_NEAR(cubic_reparameterisation(l, l, L), L, 1e-12 * L);
    const double h = 1e-6 * l;
    EXPECT_NEAR(cubic_reparameterisation(h, l, L) / h, 1.0, 1e-4 * L / l);
    EXPECT_NEAR((L - cubic_reparameterisation(l - h, l, L)) / h, 1.0, 1e-4 * L / l);
    double prev = -1;
    for (int i = 0; i <= 1000; ++i) {
      const double s = l * i / 1000.0;
      const double r = cubic_reparameterisation(s, l, L);
      EXPECT_GT(r, prev);
      prev = r;
      EXPECT_NEAR(inverse_cubic_reparameterisation(r, l, L), s, 1e-12 * L);
      // Symmetric under reversing both curves, so both sides of a cut path get the same correspondence.
      EXPECT_NEAR(L - cubic_reparameterisation(l - s, l, L), r, 1e-12 * L);
    }
  }
}

}  // namespace
}  // namespace liftmap
