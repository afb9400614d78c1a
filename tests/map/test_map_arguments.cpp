#include "map/map_arguments.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"

namespace liftmap {
namespace {

TEST(MapArguments, TextsSetTheirOptionAndMakeTheMapOptions) {
  MapArguments args;
  for (const auto& [name, value] : std::vector<std::pair<std::string, std::string>>{{"p", "inf"},
                                                                                    {"h", "eq2"},
                                                                                    {"solver", "primal-dual"},
                                                                                    {"tree", "path"},
                                                                                    {"normalize", "no"},
                                                                                    {"tolerance", "1e-4"},
                                                                                    {"max_iterations", "7"},
                                                                                    {"start_relaxation", "3"},
                                                                                    {"samples", "4"},
                                                                                    {"threads", "1"},
                                                                                    {"fix_orientation", "TRUE"}}) {
    EXPECT_EQ(set_map_argument_text(args, name, value), "") << name;
  }
  const MapOptions o = map_options(args);
  EXPECT_TRUE(std::isinf(o.flatten.p));
  EXPECT_EQ(o.flatten.h, DistortionCombiner::kMax);
  EXPECT_EQ(o.flatten.method, SubproblemSolver::kPrimalDual);
  EXPECT_EQ(o.cut.tree, CutOptions::Tree::kPath);
  EXPECT_FALSE(o.flatten.normalize_area);
  EXPECT_EQ(o.flatten.relative_tolerance, 1e-4);
  EXPECT_EQ(o.flatten.max_iterations, 7);
  EXPECT_EQ(o.flatten.joint_start.newton.max_iterations, 3);
  EXPECT_EQ(o.distortion_samples_per_edge, 4);
  EXPECT_EQ(o.threads, 1);
  EXPECT_TRUE(args.fix_orientation);
}

TEST(MapArguments, EverySpellingOfTwoAndInfinityIsANorm) {
  for (const char* two : {"2", "2.0", "2e0"}) {
    MapArguments args;
    EXPECT_EQ(set_map_argument_text(args, "p", two), "");
    EXPECT_EQ(args.choices.p, "2");
  }
  MapArguments args;
  EXPECT_EQ(set_map_argument_text(args, "p", "Infinity"), "");
  EXPECT_EQ(args.choices.p, "inf");
}

TEST(MapArguments, RefusedTextsSayWhyAndLeaveTheOptionAlone) {
  const std::vector<std::array<std::string, 3>> cases = {
      {"max_iterations", "-1", "value -1 not in range 0 to 10000"},
      {"max_iterations", "1.5", "value 1.5 is not an integer"},
      {"max_iterations", "99999999999999999999", "value 99999999999999999999 is not an integer"},
      {"samples", "11", "value 11 not in range 1 to 10"},
      {"start_relaxation", "x", "value x is not an integer"},
      {"threads", "0", "value 0 not in range 1 to"},
      {"tolerance", "nan", "value nan is not a finite number > 0"},
      {"tolerance", "-1e-3", "value -1e-3 is not a finite number > 0"},
      {"tolerance", "1e-3x", "value 1e-3x is not a finite number > 0"},
      {"p", "3", "'3' is not one of 2, inf"},
      {"tree", "star", "'star' is not one of mst, path"},
      {"normalize", "maybe", "value maybe is not one of true, false"},
      {"colour", "red", "not an option of a map"},
  };
  for (const auto& [name, value, reason] : cases) {
    MapArguments args;
    const MapArguments before = args;
    EXPECT_NE(set_map_argument_text(args, name, value).find(reason), std::string::npos) << name << " " << value;
    EXPECT_EQ(args.max_iterations, before.max_iterations);
    EXPECT_EQ(args.samples, before.samples);
    EXPECT_EQ(args.tolerance, before.tolerance);
    EXPECT_FALSE(args.threads.has_value());
    EXPECT_THROW(set_map_argument(args, name, value), UsageError);
  }
}

TEST(MapArguments, MapOptionsNamesTheFirstOptionOutOfRange) {
  MapArguments args;
  args.samples = 0;
  try {
    map_options(args);
    FAIL() << "no exception";
  } catch (const UsageError& e) {
    EXPECT_STREQ(e.what(), "samples: value 0 not in range 1 to 10");
  }
  args.samples = 2;
  args.tolerance = std::numeric_limits<double>::infinity();
  EXPECT_THROW(map_options(args), UsageError);
}

TEST(MapArguments, EverySpecNameIsAccepted) {
  for (const MapArgumentSpec& s : map_argument_specs()) {
    MapArguments args;
    const std::string value = s.is_flag ? "true" : s.name == "tolerance" ? "0.5" : s.type == "INT" ? "1" : "";
    if (value.empty()) continue;  // the choices, tested above
    EXPECT_EQ(set_map_argument_text(args, s.name, value), "") << s.name;
  }
}

}  // namespace
}  // namespace liftmap
