#pragma once
/// One key per undirected edge, for the sets and maps of path edges of the cut stage.

#include <algorithm>
#include <cstdint>

namespace liftmap {

/// Key of the edge between vertices u and w, the same for (u, w) and (w, u).
/// \pre u >= 0 and w >= 0
inline std::uint64_t edge_key(int u, int w) {
  const auto lo = static_cast<std::uint64_t>(std::min(u, w));
  const auto hi = static_cast<std::uint64_t>(std::max(u, w));
  return (lo << 32) | hi;
}

}  // namespace liftmap
