#include "core/overlay.h"

#include <string>

#include "core/errors.h"

namespace liftmap {

namespace {

/// Weights of the face point `p` (of face `g`) moved to the corners of face `f` that are the same vertices.
std::array<double, 3> reexpress(const SurfacePoint& p, const Eigen::MatrixXi& F, int f) {
  if (p.face.idx == f) return p.bary;
  std::array<double, 3> w{0, 0, 0};
  double lost = 0;
  for (int k = 0; k < 3; ++k) {
    const double b = p.bary[static_cast<size_t>(k)];
    bool found = false;
    for (int j = 0; j < 3; ++j) {
      if (F(p.face.idx, k) == F(f, j)) {
        w[static_cast<size_t>(j)] += b;
        found = true;
      }
    }
    if (!found) lost += b;
  }
  if (lost > 1e-9) {
    throw PipelineError("overlay: a vertex recorded in face " + std::to_string(p.face.idx) + " is not on face " +
                        std::to_string(f) + " (weight " + std::to_string(lost) + " elsewhere)");
  }
  return clamp_barycentric(w);
}

}  // namespace

std::array<std::array<double, 3>, 3> corner_barycentrics(const Overlay& overlay, const Eigen::MatrixXi& F, Side side,
                                                         int t) {
  const bool a = side == Side::kA;
  const int f = a ? overlay.face_a(t) : overlay.face_b(t);
  const std::vector<SurfacePoint>& points = a ? overlay.on_a : overlay.on_b;
  std::array<std::array<double, 3>, 3> out{};
  for (int k = 0; k < 3; ++k)
    out[static_cast<size_t>(k)] = reexpress(points[static_cast<size_t>(overlay.F(t, k))], F, f);
  return out;
}

}  // namespace liftmap
