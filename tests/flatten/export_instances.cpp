// Writes the convex subproblems (10) of the differential test (cvxopt_reference.py), solved by our barrier
// method: several real patch pairs (different connectivities, equal boundary counts) times all four (p, h).
// Usage: export_instances OUTPUT_DIR

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>

#include "disk_patches.h"
#include "flatten/barrier_solver.h"
#include "flatten/joint_flatten.h"
#include "flatten/primal_dual_solver.h"
#include "subproblem_export.h"

int main(int argc, char** argv) {
  using namespace liftmap;
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_DIR\n", argv[0]);
    return 2;
  }
  const std::filesystem::path dir(argv[1]);
  std::filesystem::create_directories(dir);
  struct PairSpec {
    const char* name;
    const char* a;
    const char* b;
    int faces, seed_a, seed_b;
  };
  // CVXOPT's SOCP solver is dense in the number of variables (about 7 per face): keep the pairs small enough
  // for the reference to run in about a minute, with different connectivities and equal boundary counts.
  const PairSpec pairs[] = {{"camel_cow", "camel.off", "cow.off", 100, 0, 500},
                            {"bull_dino", "bull.off", "dino.off", 80, 10, 100},
                            {"man_elephant", "man.off", "elephant.off", 120, 2000, 30}};
  for (const PairSpec& ps : pairs) {
    const auto [a, b] = testing::patch_pair(ps.a, ps.b, ps.faces, ps.seed_a, ps.seed_b);
    for (const testing::Combo& c : testing::kAllCombos) {
      JointFlattenOptions opt;
      opt.p = c.p;
      opt.h = c.h;
      const JointFlattenProblem jp = make_joint_flatten_problem(a.flattening_disk(), b.flattening_disk(), opt);
      SparseCholesky chol;
      const auto t0 = std::chrono::steady_clock::now();
      const SubproblemResult r = solve_convex_subproblem(jp.subproblem, jp.X0, SubproblemSettings{}, chol);
      const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      SparseCholesky chol_pd;
      const SubproblemResult pd =
          solve_convex_subproblem_primal_dual(jp.subproblem, jp.X0, SubproblemSettings{}, chol_pd);
      const std::string file = (dir / (std::string(ps.name) + "_" + c.name + ".json")).string();
      export_subproblem(file, jp.subproblem, jp.X0, r, &pd);
      std::printf(
          "%s: %d + %d faces, objective %.12g, gap bound %.1e, %d Newton steps, %.3f s%s; primal-dual %.12g, "
          "gap %.1e, %d iterations%s\n",
          file.c_str(), static_cast<int>(a.F.rows()), static_cast<int>(b.F.rows()), r.objective, r.gap_bound,
          r.iterations, sec, r.converged() ? "" : " (stopped before the 1e-8 gap)", pd.objective, pd.gap_bound,
          pd.iterations, pd.converged() ? "" : " (stopped before the 1e-8 gap)");
    }
  }
  return 0;
}
