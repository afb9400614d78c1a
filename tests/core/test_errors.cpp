#include "core/errors.h"

#include <gtest/gtest.h>

namespace liftmap {
namespace {

TEST(Errors, FiguresInMessagesKeepTheirSignificantDigits) {
  // The exit-5 message once printed "round trip error 0.000000 >= 1e-9" for 6e-9.
  EXPECT_EQ(figure(6e-9), "6e-09");
  EXPECT_EQ(figure(1.234567e12), "1.23e+12");
  EXPECT_EQ(figure(0.5), "0.5");
  EXPECT_EQ(figure(1234, 17), "1234");
  EXPECT_EQ(figure(-1.5e-300), "-1.5e-300");
}

TEST(Errors, EdgesAreNamedByTheirVertices) { EXPECT_EQ(edge_name(3, 12), "(3, 12)"); }

}  // namespace
}  // namespace liftmap
