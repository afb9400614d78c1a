// Benchmark of the joint flattening (not a test): time per outer iteration and in total on a camel-cow pair
// (whole meshes minus a small disk) and on a pair of ~25k-face patches, and our time on the first subproblem
// of a ~2k-face-per-mesh pair, exported for cvxopt_time.py to time CVXOPT on the same instance.
// Usage: bench_flatten OUTPUT_DIR   (run_bench.sh runs both sides)

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "disk_patches.h"
#include "flatten/barrier_solver.h"
#include "flatten/joint_flatten.h"
#include "flatten/subproblem_export.h"

namespace {

using namespace liftmap;

void run_pair(const char* name, const testing::TestDisk& a, const testing::TestDisk& b) {
  std::printf("%s: %d + %d faces, %zu boundary vertices\n", name, static_cast<int>(a.F.rows()),
              static_cast<int>(b.F.rows()), a.boundary.size());
  const auto t0 = std::chrono::steady_clock::now();
  const JointFlattenResult r = joint_flatten(a.flattening_disk(), b.flattening_disk());
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  double solve = 0;
  for (size_t i = 0; i < r.iterations.size(); ++i) {
    const auto& it = r.iterations[i];
    solve += it.seconds;
    std::printf("  outer %zu: energy %.6f  max distortion %.3f  Newton steps %3d  %.2f s\n", i, it.energy,
                it.max_distortion, it.newton_steps, it.seconds);
  }
  const int outer = static_cast<int>(r.iterations.size()) - 1;
  std::printf("  total %.2f s (Tutte + setup %.2f s), %d outer iterations, %.2f s per outer iteration\n", total,
              total - solve, outer, solve / outer);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_DIR\n", argv[0]);
    return 2;
  }
  std::filesystem::create_directories(argv[1]);
  {
    // First subproblem at ~2k faces per mesh: ours, timed here; CVXOPT timed by cvxopt_time.py.
    const auto [a, b] = testing::patch_pair("camel.off", "cow.off", 2000, 0, 500);
    const JointFlattenProblem jp = make_joint_flatten_problem(a.flattening_disk(), b.flattening_disk(), {});
    SparseCholesky chol;
    const auto t0 = std::chrono::steady_clock::now();
    const BarrierResult r = solve_convex_subproblem(jp.subproblem, jp.X0, BarrierOptions{}, chol);
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("first subproblem, %d + %d faces: ours %.3f s, objective %.10g, %d Newton steps, gap bound %.1e\n",
                static_cast<int>(a.F.rows()), static_cast<int>(b.F.rows()), sec, r.objective, r.newton_steps,
                r.gap_bound);
    const std::string file = std::string(argv[1]) + "/first_subproblem_2k.json";
    export_subproblem(file, jp.subproblem, jp.X0, r);
    std::printf("ours_seconds %.6f\n", sec);
  }
  {
    const auto [a, b] = testing::punctured_pair("camel.off", "cow.off", 20);
    run_pair("camel-cow (closed meshes minus a small disk)", a, b);
  }
  {
    const testing::TestDisk a = testing::mesh_patch("armadillo.off", 0, 25000);
    const testing::TestDisk b = testing::mesh_patch("man.off", 0, 24000, static_cast<int>(a.boundary.size()));
    run_pair("armadillo-man patches (~25k faces each)", a, b);
  }
  return 0;
}
