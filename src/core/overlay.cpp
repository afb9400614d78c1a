#include "core/overlay.h"

namespace liftmap {

std::array<std::array<double, 3>, 3> corner_barycentrics(const Overlay& overlay, const Eigen::MatrixXi& F, Side side,
                                                         int t) {
  const bool a = side == Side::kA;
  const int f = a ? overlay.face_a(t) : overlay.face_b(t);
  const std::vector<SurfacePoint>& points = a ? overlay.on_a : overlay.on_b;
  std::array<std::array<double, 3>, 3> out{};
  for (int k = 0; k < 3; ++k)
    out[static_cast<size_t>(k)] = reexpress_in_face(points[static_cast<size_t>(overlay.F(t, k))], F, f);
  return out;
}

}  // namespace liftmap
