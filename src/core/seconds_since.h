#pragma once
/// Wall-clock intervals of the pipeline's timings (report.json's seconds, progress lines).

#include <chrono>

namespace liftmap {

/// Seconds of std::chrono::steady_clock since `start`.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace liftmap
