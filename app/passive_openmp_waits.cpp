#include "passive_openmp_waits.h"

#include <unistd.h>

#include <cstdlib>

namespace liftmap_app {

void run_with_passive_openmp_waits(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr || std::getenv("GOMP_SPINCOUNT") != nullptr) return;
  if (setenv("OMP_WAIT_POLICY", "passive", 1) != 0) return;
  execv("/proc/self/exe", argv);
  unsetenv("OMP_WAIT_POLICY");  // no /proc: libgomp's default policy, as before
}

}  // namespace liftmap_app
