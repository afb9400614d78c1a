#include "flatten/supernodal_factorization.h"

#include <stdexcept>

#include "flatten/supernodal_numeric.h"

namespace liftmap {

namespace {

SupernodeOrder order_of(const std::vector<int>& supernodes) {
  return {.supernodes = supernodes.data(), .count = static_cast<int>(supernodes.size())};
}

}  // namespace

bool avx2_kernels_available() {
#ifdef LIFTMAP_AVX2_KERNELS
  // GCC's and clang's checks include the operating system's support for the AVX registers (XGETBV).
  static const bool available = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return available;
#else
  return false;
#endif
}

void require_dense_kernels(DenseKernels kernels) {
  if (kernels == DenseKernels::kAvx2 && !avx2_kernels_available())
    throw std::invalid_argument("dense kernels: AVX2 asked for, but this build or this CPU has no AVX2 kernels");
}

int factorize_supernodal(const LowerColumns& B, const SupernodalStructure& L, double* x,
                         const SupernodeSchedule& schedule, DenseKernels kernels) {
  require_dense_kernels(kernels);
  const SupernodeOrder group0 = order_of(schedule.groups[0]), group1 = order_of(schedule.groups[1]),
                       top = order_of(schedule.top);
#ifdef LIFTMAP_AVX2_KERNELS
  if (kernels != DenseKernels::kBaseline && avx2_kernels_available())
    return avx2::factorize_numeric(B, L, x, group0, group1, top);
#endif
  return baseline::factorize_numeric(B, L, x, group0, group1, top);
}

}  // namespace liftmap
