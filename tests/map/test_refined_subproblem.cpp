// The second subproblem of a large smooth pair: sphere-ellipsoid refined to about 60k faces per mesh by the bench's
// subdivide_mesh (the ctest fixture map.refined_pair_meshes writes it to the folder LIFTMAP_REFINED_PAIR names;
// about a minute, so only with ctest -L slow). After its first outer iteration the energy fell by 3.5% but the next
// iteration can gain only about 2e-4: a second subproblem started at a fraction of the last gain (the barrier
// parameter of start_gap_fraction alone) ends above its start and is solved again, finer (docs/algorithm.md, "When a
// subproblem ends above its start"); started at a few times the rotation gain (rotation_gain_start_fraction, the
// default) it ends below its start in a single centring.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "io/landmarks.h"
#include "io/read_mesh.h"
#include "map/map_meshes.h"
#include "map/write_map.h"

namespace liftmap {
namespace {

struct RefinedPair {
  TriangleMesh a, b;
  Landmarks landmarks;
};

RefinedPair refined_pair() {
  const char* folder = std::getenv("LIFTMAP_REFINED_PAIR");
  if (folder == nullptr) throw std::runtime_error("LIFTMAP_REFINED_PAIR is not set (run through ctest -L slow)");
  const std::string dir(folder);
  RefinedPair p{read_mesh(dir + "/A.off"), read_mesh(dir + "/B.off"), {}};
  p.landmarks = read_landmarks(dir + "/landmarks.txt", static_cast<int>(p.a.V.rows()), static_cast<int>(p.b.V.rows()));
  return p;
}

MapOptions map_options(double rotation_gain_start_fraction) {
  MapOptions options;
  options.overlay = false;  // the overlay does not take part in the flattening; the verification still runs
  options.flatten.rotation_gain_start_fraction = rotation_gain_start_fraction;
  return options;
}

/// Every outer iteration lowered the energy, the loop converged by its rule and the map passed its verification.
void expect_converged_map(const MapResult& m) {
  const JointFlattenResult& fl = m.flattening;
  for (size_t i = 1; i < fl.iterations.size(); ++i) {
    EXPECT_LE(fl.iterations[i].energy, fl.iterations[i - 1].energy) << "outer iteration " << i;
    EXPECT_TRUE(fl.iterations[i].subproblem_converged) << "outer iteration " << i;
  }
  EXPECT_TRUE(fl.converged) << fl.stop_reason;
  EXPECT_TRUE(fl.stop_reason.empty()) << fl.stop_reason;
  EXPECT_TRUE(m.verification.passed);
}

/// The map whose second subproblem started from the last gain alone took the refined path, and its report.json says
/// so (what tests/cli/refined_subproblem.sh checked through the CLI while the defaults took that path).
void expect_refined_path(const RefinedPair& p, const MapResult& m, const MapOptions& options) {
  const JointFlattenResult& fl = m.flattening;
  const double tolerance = options.flatten.relative_tolerance;
  bool refined = false;
  for (size_t i = 1; i < fl.iterations.size(); ++i) {
    const JointFlattenIteration& it = fl.iterations[i];
    if (!it.subproblem_refined) continue;
    refined = true;
    EXPECT_TRUE(it.subproblem_converged);
    EXPECT_LE(it.subproblem_gap, 0.5 * tolerance);
    EXPECT_LT(it.subproblem_objective, fl.iterations[i - 1].energy);
  }
  // Either the second solve ended below its start (an iteration marked refined) or above it too (converged there).
  EXPECT_TRUE(refined || fl.last_subproblem_steps > 0) << "no subproblem was solved again: the pair no longer "
                                                          "exercises the path";
  expect_converged_map(m);
  const nlohmann::json report = map_report(m, "A.off", p.a, "B.off", p.b, p.landmarks, options);
  const nlohmann::json& its = report["flatten"]["iterations"];
  ASSERT_EQ(its.size(), fl.iterations.size());
  for (size_t i = 0; i < fl.iterations.size(); ++i) {
    EXPECT_EQ(its[i]["subproblem_refined"].get<bool>(), fl.iterations[i].subproblem_refined) << "iteration " << i;
  }
  EXPECT_EQ(report["flatten"]["last_subproblem_steps"].get<int>(), fl.last_subproblem_steps);
  EXPECT_TRUE(report["flatten"]["converged"].get<bool>());
  EXPECT_TRUE(report["verification"]["passed"].get<bool>());
  EXPECT_EQ(report["options"]["rotation_gain_start_fraction"].get<double>(), 0);
}

/// The default map of the same pair: no refined path, fewer Newton steps in the second outer iteration than `other`
/// (the map from the last gain alone), the same first iteration and a final energy within the tolerance of it.
void expect_no_refined_path(const MapResult& m, const MapResult& other) {
  expect_converged_map(m);
  const JointFlattenResult& fl = m.flattening;
  ASSERT_GE(fl.iterations.size(), 3U);
  ASSERT_GE(other.flattening.iterations.size(), 3U);
  for (size_t i = 1; i < fl.iterations.size(); ++i) EXPECT_FALSE(fl.iterations[i].subproblem_refined);
  EXPECT_EQ(fl.last_subproblem_steps, 0);
  EXPECT_EQ(fl.iterations[1].energy, other.flattening.iterations[1].energy);
  EXPECT_LT(fl.iterations[2].newton_steps, other.flattening.iterations[2].newton_steps);
  const double e = fl.iterations.back().energy, e_other = other.flattening.iterations.back().energy;
  EXPECT_LT(std::abs(e - e_other), JointFlattenOptions{}.relative_tolerance * e_other);
}

// One test, so that one process maps the pair once each way (ctest runs every test in a process of its own).
TEST(map_refined_subproblem, RefinedSolveFromTheLastGainAndNoneFromTheRotationGain) {
  const RefinedPair p = refined_pair();
  const MapOptions by_gain_options = map_options(0);
  const MapResult by_gain = map_meshes(p.a.V, p.a.F, p.b.V, p.b.F, p.landmarks.a, p.landmarks.b, by_gain_options);
  {
    SCOPED_TRACE("start_gap_fraction alone: the refined path");
    expect_refined_path(p, by_gain, by_gain_options);
  }
  const MapResult by_rotations = map_meshes(p.a.V, p.a.F, p.b.V, p.b.F, p.landmarks.a, p.landmarks.b,
                                            map_options(JointFlattenOptions{}.rotation_gain_start_fraction));
  SCOPED_TRACE("the default start from the rotation gain: no refined path");
  expect_no_refined_path(by_rotations, by_gain);
}

}  // namespace
}  // namespace liftmap
