#include "io/mesh_fingerprint.h"

#include <cinttypes>
#include <cstdio>
#include <cstdlib>

namespace liftmap {

namespace {

constexpr std::uint64_t kFnvOffset = 14695981039346656037ULL;
constexpr std::uint64_t kFnvPrime = 1099511628211ULL;

/// FNV-1a over the 4 little-endian bytes of `value`.
std::uint64_t hash_int(std::uint64_t h, std::uint32_t value) {
  for (int byte = 0; byte < 4; ++byte) {
    h ^= (value >> (8 * byte)) & 0xFFU;
    h *= kFnvPrime;
  }
  return h;
}

}  // namespace

MeshFingerprint mesh_fingerprint(Eigen::Index n_vertices, const Eigen::MatrixXi& F) {
  std::uint64_t h = kFnvOffset;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    for (Eigen::Index c = 0; c < F.cols(); ++c) h = hash_int(h, static_cast<std::uint32_t>(F(f, c)));
  }
  return {static_cast<long long>(n_vertices), static_cast<long long>(F.rows()), h};
}

std::string to_string(const MeshFingerprint& fingerprint) {
  char text[128];
  std::snprintf(text, sizeof text, "%lld vertices, %lld faces, connectivity fnv1a64:%016" PRIx64, fingerprint.vertices,
                fingerprint.faces, fingerprint.connectivity);
  return text;
}

std::optional<MeshFingerprint> parse_mesh_fingerprint(const std::string& text) {
  MeshFingerprint fp;
  char hex[17] = {};
  int consumed = 0;
  if (std::sscanf(text.c_str(), "%lld vertices, %lld faces, connectivity fnv1a64:%16[0-9a-fA-F]%n", &fp.vertices,
                  &fp.faces, hex, &consumed) != 3 ||
      static_cast<size_t>(consumed) != text.size() || std::string(hex).size() != 16 || fp.vertices < 0 ||
      fp.faces < 0) {
    return std::nullopt;
  }
  fp.connectivity = std::strtoull(hex, nullptr, 16);
  return fp;
}

}  // namespace liftmap
