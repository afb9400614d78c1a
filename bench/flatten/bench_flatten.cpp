// Benchmark of the joint flattening's convex subproblem against a general-purpose conic solver (not a test): for
// each requested size n, the first subproblem of a camel patch of n faces and a smooth non-isometric deformation
// of it (same connectivity, so both meshes have n faces; camel-cow patch pairs with equal boundary counts grow the
// cow side to the whole cow) is solved by our barrier method (median of three runs) and exported for
// cvxopt_time.py, which times CVXOPT on the same instance. The end-to-end flattening of whole pairs is timed by
// bench/run.py through `liftmap map`, and profile_flatten gives its per-centring profile. Usage: bench_flatten
// OUTPUT_DIR [FACES_PER_MESH...]   (default 2000; writes OUTPUT_DIR/first_subproblem_N.json)

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "disk_patches.h"
#include "flatten/barrier_solver.h"
#include "flatten/joint_flatten.h"
#include "subproblem_export.h"

int main(int argc, char** argv) {
  using namespace liftmap;
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_DIR [FACES_PER_MESH...]\n", argv[0]);
    return 2;
  }
  std::filesystem::create_directories(argv[1]);
  std::vector<int> sizes;
  for (int i = 2; i < argc; ++i) sizes.push_back(std::stoi(argv[i]));
  if (sizes.empty()) sizes.push_back(2000);
  for (const int n : sizes) {
    const testing::TestDisk a = testing::mesh_patch("camel.off", 0, n);
    const testing::TestDisk b = testing::deformed_copy(a);
    const JointFlattenProblem jp = make_joint_flatten_problem(a.flattening_disk(), b.flattening_disk(), {});
    std::vector<double> seconds;
    SubproblemResult r;
    for (int rep = 0; rep < 3; ++rep) {
      SparseCholesky chol;
      const auto t0 = std::chrono::steady_clock::now();
      r = solve_convex_subproblem(jp.subproblem, jp.X0, SubproblemSettings{}, chol);
      seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    std::sort(seconds.begin(), seconds.end());
    const std::string file = std::string(argv[1]) + "/first_subproblem_" + std::to_string(n) + ".json";
    export_subproblem(file, jp.subproblem, jp.X0, r);
    // One line per instance, read by bench/run.py: size, faces, our median time, objective, steps, gap bound, file.
    std::printf("instance %d faces %d %d ours_seconds %.6f objective %.12g newton_steps %d gap_bound %.2e file %s\n", n,
                static_cast<int>(a.F.rows()), static_cast<int>(b.F.rows()), seconds[1], r.objective, r.iterations,
                r.gap_bound, file.c_str());
    std::fflush(stdout);
  }
  return 0;
}
