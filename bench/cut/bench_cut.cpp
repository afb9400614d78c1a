// Timing of step 1 (cut both meshes to disks): camel-cow with 20 seeded random landmarks, and a pair of about
// 25k vertices each (armadillo-armadillo). Not a test: prints times, exits 0.
//   bench_cut [DATA_DIR] [k]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <random>
#include <string>

#include "cut/cut_meshes.h"
#include "io/read_mesh.h"

namespace {

void run(const std::string& dir, const char* a, const char* b, int k) {
  const auto ma = liftmap::read_mesh(dir + "/" + a + ".off");
  const auto mb = liftmap::read_mesh(dir + "/" + b + ".off");
  std::mt19937 rng(20);
  std::vector<liftmap::VertexId> la, lb;
  for (int i = 0; i < k; ++i) {
    la.emplace_back(static_cast<int>(rng() % static_cast<unsigned>(ma.V.rows())));
    lb.emplace_back(static_cast<int>(rng() % static_cast<unsigned>(mb.V.rows())));
  }
  for (const bool geodesic : {true, false}) {
    liftmap::CutOptions options;
    options.geodesic_paths = geodesic;
    // Best of three runs (the first pays for page faults; shared machines add noise).
    double s = 1e30, cpu = 1e30;
    liftmap::CutResult r;
    for (int rep = 0; rep < 3; ++rep) {
      const auto t0 = std::chrono::steady_clock::now();
      const std::clock_t c0 = std::clock();
      r = liftmap::cut_meshes(ma.V, ma.F, mb.V, mb.F, la, lb, options);
      s = std::min(s, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      cpu = std::min(cpu, static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
    }
    double len_a = 0, len_b = 0;
    for (const double l : r.a.path_lengths) len_a += l;
    for (const double l : r.b.path_lengths) len_b += l;
    std::printf(
        "%s-%s k=%d %s: %.3f s wall, %.3f s CPU  (%lld + %lld vertices, %zu boundary pairs, tree length %.4g + %.4g)\n",
        a, b, k, geodesic ? "geodesic paths" : "edge paths   ", s, cpu, static_cast<long long>(ma.V.rows()),
        static_cast<long long>(mb.V.rows()), r.nu.size(), len_a, len_b);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : LIFTMAP_DATA_DIR;
  const int k = argc > 2 ? std::stoi(argv[2]) : 20;
  run(dir, "camel", "cow", k);
  run(dir, "armadillo", "armadillo", k);
  return 0;
}
