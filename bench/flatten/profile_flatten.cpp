// Profile of step 2 on a real pair (not a test): cuts the pair along its example landmarks, then runs the joint
// flattening and prints, per outer iteration, every centring of the barrier method: its barrier parameter, Newton
// steps, damped steps, repaired steps, and time. This is where bench/RESULTS.md's "where the time goes" comes from.
// Usage: profile_flatten A.off B.off landmarks.txt [max_outer_iterations [barrier_growth [relative_gap]]]
// Environment: PROFILE_STEPS=1 prints every step; PROFILE_SOLVER=primal-dual uses the primal-dual solver (a "centring"
// line is then one of its iterations, with t = 1 / mu); PROFILE_P_INF=1 solves for p = inf; PROFILE_GAP_FRACTION=x sets
// JointFlattenOptions::gap_fraction (0: every subproblem to relative_gap); PROFILE_START_GAP_FRACTION=x sets
// JointFlattenOptions::start_gap_fraction (0: every subproblem starts at the usual barrier parameter);
// PROFILE_RELAXED_START_GAP_FRACTION=x sets JointFlattenOptions::relaxed_start_gap_fraction (0: off);
// PROFILE_ROTATION_GAIN_START_FRACTION=x sets JointFlattenOptions::rotation_gain_start_fraction (0: off);
// PROFILE_MAX_SUBPROBLEM_GAP=x sets JointFlattenOptions::max_subproblem_gap; PROFILE_REFINED_GAP_FRACTION=x sets
// JointFlattenOptions::refined_gap_fraction; PROFILE_ISOTROPIC=0 turns off
// BarrierSettings::isotropic_anticonformal_curvature; PROFILE_REMESH=0 turns off CutOptions::remesh;
// PROFILE_START_STEPS=n sets JointFlattenOptions::start_optimization.max_iterations (0: off);
// PROFILE_DUAL_GAP_DECREMENT=x sets BarrierSettings::dual_gap_decrement (0: off).

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

#include "cut/cut_meshes.h"
#include "flatten/joint_flatten.h"
#include "io/landmarks.h"
#include "io/read_mesh.h"

int main(int argc, char** argv) {
  using namespace liftmap;
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s A B landmarks.txt [max_outer_iterations [barrier_growth [relative_gap]]]\n",
                 argv[0]);
    return 2;
  }
  const TriangleMesh A = read_mesh(argv[1]);
  const TriangleMesh B = read_mesh(argv[2]);
  const Landmarks L = read_landmarks(argv[3], static_cast<int>(A.V.rows()), static_cast<int>(B.V.rows()));
  auto t0 = std::chrono::steady_clock::now();
  CutOptions cut_options;
  if (const char* g = std::getenv("PROFILE_REMESH")) cut_options.remesh = std::atoi(g) != 0;
  const CutResult cut = cut_meshes(A.V, A.F, B.V, B.F, L.a, L.b, cut_options);
  const double cut_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const Mesh disk_a(cut.a.F_cut, static_cast<int>(cut.a.cut_to_refined.size()));
  const Mesh disk_b(cut.b.F_cut, static_cast<int>(cut.b.cut_to_refined.size()));
  FlatteningDisk m{&disk_a, cut.a.V(cut.a.cut_to_refined, Eigen::all), {}};
  FlatteningDisk n{&disk_b, cut.b.V(cut.b.cut_to_refined, Eigen::all), {}};
  for (const auto& pair : cut.nu) {
    m.boundary.emplace_back(pair[0]);
    n.boundary.emplace_back(pair[1]);
  }
  std::printf("cut %.2f s: disks of %d + %d faces, %zu boundary pairs\n", cut_s, disk_a.n_faces(), disk_b.n_faces(),
              cut.nu.size());

  JointFlattenOptions options;
  if (argc > 4) options.max_iterations = std::atoi(argv[4]);
  if (argc > 5) options.solver.barrier.barrier_growth = std::atof(argv[5]);
  if (argc > 6) options.solver.relative_gap = std::atof(argv[6]);
  if (const char* m = std::getenv("PROFILE_SOLVER"); m != nullptr && std::string(m) == "primal-dual") {
    options.method = SubproblemSolver::kPrimalDual;
  }
  if (const char* g = std::getenv("PROFILE_GAP_FRACTION")) options.gap_fraction = std::atof(g);
  if (const char* g = std::getenv("PROFILE_START_GAP_FRACTION")) options.start_gap_fraction = std::atof(g);
  if (const char* g = std::getenv("PROFILE_RELAXED_START_GAP_FRACTION")) {
    options.relaxed_start_gap_fraction = std::atof(g);
  }
  if (const char* g = std::getenv("PROFILE_ROTATION_GAIN_START_FRACTION")) {
    options.rotation_gain_start_fraction = std::atof(g);
  }
  if (const char* g = std::getenv("PROFILE_MAX_SUBPROBLEM_GAP")) options.max_subproblem_gap = std::atof(g);
  if (const char* g = std::getenv("PROFILE_REFINED_GAP_FRACTION")) options.refined_gap_fraction = std::atof(g);
  if (const char* g = std::getenv("PROFILE_RELAXATION_DECREASE")) {
    options.joint_start.newton.relative_decrease = std::atof(g);
  }
  if (const char* g = std::getenv("PROFILE_DUAL_GAP_DECREMENT")) {
    options.solver.barrier.dual_gap_decrement = std::atof(g);
  }
  if (const char* g = std::getenv("PROFILE_PROXY_WHILE_DECREASE")) {
    options.start_optimization.proxy_while_decrease = options.joint_start.newton.proxy_while_decrease = std::atof(g);
  }
  if (const char* g = std::getenv("PROFILE_START_STEPS")) options.start_optimization.max_iterations = std::atoi(g);
  if (const char* g = std::getenv("PROFILE_ISOTROPIC"))
    options.solver.barrier.isotropic_anticonformal_curvature = std::atoi(g) != 0;
  if (std::getenv("PROFILE_P_INF")) options.p = std::numeric_limits<double>::infinity();
  if (const char* g = std::getenv("PROFILE_PD_REFINEMENTS")) options.solver.primal_dual.max_refinements = std::atoi(g);
  int outer = 1;
  struct Centring {
    int index = -1, steps = 0, damped = 0, repaired = 0;
    double t = 0, seconds = 0, min_step = 1, objective = 0, derivatives = 0, factorization = 0, line_search = 0;
  } c;
  auto flush = [&] {
    if (c.index < 0) return;
    std::printf(
        "  centring %2d  t %9.3g  steps %3d  damped(<1) %3d  repaired %3d  min step %8.2g  %6.2f s (derivatives %.2f, "
        "factorisation %.2f, line search %.2f)  f0 %.6g\n",
        c.index, c.t, c.steps, c.damped, c.repaired, c.min_step, c.seconds, c.derivatives, c.factorization,
        c.line_search, c.objective);
  };
  options.solver.on_step = [&](const SubproblemStep& s) {
    if (s.centring != c.index) {
      flush();
      if (s.centring < c.index) std::printf("outer iteration %d\n", ++outer);
      c = Centring{.index = s.centring, .t = s.t};
    }
    if (std::getenv("PROFILE_STEPS")) {
      std::printf("    step: lambda2 %10.4g  step %8.3g%s%s  f0 %.6g\n", s.lambda2, s.step,
                  s.repaired ? " repaired" : "", s.isotropic ? " isotropic" : "", s.objective);
    }
    ++c.steps;
    c.seconds += s.seconds;
    c.derivatives += s.seconds_derivatives;
    c.factorization += s.seconds_factorization;
    c.line_search += s.seconds_line_search;
    c.objective = s.objective;
    if (s.step > 0 && s.step < 1) ++c.damped;
    if (s.repaired) ++c.repaired;
    if (s.step > 0) c.min_step = std::min(c.min_step, s.step);
  };
  std::printf("outer iteration 1\n");
  t0 = std::chrono::steady_clock::now();
  const JointFlattenResult r = joint_flatten(m, n, options);
  flush();
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (size_t i = 0; i < r.iterations.size(); ++i) {
    const auto& it = r.iterations[i];
    std::printf(
        "iterate %zu: energy %.6f  max distortion %.4g  gap %.2g  Newton steps %d  %.2f s  subproblem objective "
        "%.6f%s\n",
        i, it.energy, it.max_distortion, it.subproblem_gap, it.newton_steps, it.seconds, it.subproblem_objective,
        it.subproblem_refined ? " (refined)" : "");
  }
  std::printf("start: per-disk steps %d + %d, joint relaxation %d steps, %.2f s\n", r.start_steps[0], r.start_steps[1],
              r.joint_start.steps, r.joint_start.seconds);
  std::printf("flatten total %.2f s %s\n", total, r.stop_reason.c_str());
  return 0;
}
