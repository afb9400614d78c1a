// Benchmark of bijection lifting (paper §3.2), both directions, on Tutte pairs of real mesh patches.
// Usage: bench_lift [meshes folder]   (default: the compile-time LIFTMAP_DATA_DIR)

#include <Eigen/Core>
#include <chrono>
#include <cstdio>
#include <string>

#include "core/mesh.h"
#include "io/read_mesh.h"
#include "lift/lift_map.h"
#include "lift_fixtures.h"

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

void run(const std::string& name, const liftmap::testing::FlatPair& p) {
  using liftmap::LiftedBijection;
  const liftmap::Mesh m(p.m.F, static_cast<int>(p.m.X.rows()));
  const liftmap::Mesh n(p.n.F, static_cast<int>(p.n.X.rows()));
  std::printf("%s: M^ %d vertices %d faces, N^ %d vertices %d faces, %d boundary vertices\n", name.c_str(),
              m.n_vertices(), m.n_faces(), n.n_vertices(), n.n_faces(), static_cast<int>(p.nu.rows()));
  for (const bool verify : {false, true}) {
    double best = 1e300;
    for (int rep = 0; rep < 5; ++rep) {
      const auto t0 = Clock::now();
      const LiftedBijection lift(m, p.m.X, n, p.n.X, p.nu, {verify});
      best = std::min(best, ms_since(t0));
    }
    std::printf("  lift both directions (f and g at every vertex), verify=%d: %.1f ms (best of 5)\n", verify, best);
  }
  const LiftedBijection lift(m, p.m.X, n, p.n.X, p.nu, {false});
  const auto t0 = Clock::now();
  double sink = 0;
  for (int f = 0; f < m.n_faces(); ++f) {
    sink += lift.evaluate_f(liftmap::SurfacePoint::in_face(liftmap::FaceId(f), {0.2, 0.3, 0.5})).bary[0];
  }
  const double t = ms_since(t0);
  std::printf("  evaluate_f at one point per face of M^: %.1f ms (%.2f us per point)%s\n", t, 1000.0 * t / m.n_faces(),
              sink < -1 ? " " : "");
}

}  // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : LIFTMAP_DATA_DIR;
  using liftmap::read_mesh;
  using liftmap::testing::subdivide;
  using liftmap::testing::tutte_pair_of_patches;
  try {
    // Patches of a quarter of each surface or less: a mean-value Tutte embedding of (nearly) a whole closed
    // mesh squeezes the far side below double precision, flipping faces, and is rightly rejected as not
    // locally injective. Subdivision gives the patches the requested size.
    const auto camel = subdivide(read_mesh(dir + "/camel.off"));
    const auto cow = subdivide(subdivide(read_mesh(dir + "/cow.off")));
    run("camel / cow (subdivided), ~19.5k-face patches", tutte_pair_of_patches(camel, cow, 19500));
    const auto man = subdivide(read_mesh(dir + "/man.off"));
    const auto armadillo = subdivide(read_mesh(dir + "/armadillo.off"));
    run("man / armadillo (subdivided), ~25k-face patches", tutte_pair_of_patches(man, armadillo, 25000));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_lift: %s\n", e.what());
    return 1;
  }
  return 0;
}
