#pragma once
/// The supernodal numeric factorisation's arithmetic (supernodal_factorization.h), compiled twice: in namespace
/// liftmap::baseline for the baseline x86-64 instruction set (SSE2), and in liftmap::avx2 with AVX2 and FMA, where
/// Eigen's dense products run about twice as fast per core. Only plain types cross this interface: the AVX2 copy
/// renames Eigen's namespace and must define no symbol another object could share (see CMakeLists.txt).

#include "flatten/supernodal_factorization.h"

namespace liftmap {

/// Supernodes to factorise in this order.
struct SupernodeOrder {
  const int* supernodes = nullptr;
  int count = 0;
};

namespace baseline {
/// factorize_supernodal with the groups' and the top's supernodes as plain arrays (see SupernodeSchedule).
int factorize_numeric(const LowerColumns& B, const SupernodalStructure& L, double* x, SupernodeOrder group0,
                      SupernodeOrder group1, SupernodeOrder top);
}  // namespace baseline

namespace avx2 {
/// The same, compiled for AVX2 with FMA: call only where the CPU has both (avx2_kernels_available()).
int factorize_numeric(const LowerColumns& B, const SupernodalStructure& L, double* x, SupernodeOrder group0,
                      SupernodeOrder group1, SupernodeOrder top);
}  // namespace avx2

}  // namespace liftmap
