#include "render/colour_maps.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "core/errors.h"

namespace liftmap {
namespace {

/// RGB of a hue in [0,1) at full saturation and value, scaled into [lo, hi] per channel.
Eigen::Vector3d hue_colour(double hue, double lo, double hi) {
  const double h = 6.0 * (hue - std::floor(hue));
  const double x = 1.0 - std::abs(std::fmod(h, 2.0) - 1.0);
  Eigen::Vector3d c;
  switch (static_cast<int>(h) % 6) {
    case 0:
      c = {1, x, 0};
      break;
    case 1:
      c = {x, 1, 0};
      break;
    case 2:
      c = {0, 1, x};
      break;
    case 3:
      c = {0, x, 1};
      break;
    case 4:
      c = {x, 0, 1};
      break;
    default:
      c = {1, 0, x};
      break;
  }
  return Eigen::Vector3d::Constant(lo) + (hi - lo) * c;
}

}  // namespace

Eigen::Vector3d CheckerTexture::operator()(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d extent = (box_max - box_min).cwiseMax(1e-300);
  const Eigen::Vector3d u = ((p - box_min).cwiseQuotient(extent)).cwiseMax(0.0).cwiseMin(1.0);
  // Hue runs along the longest axis, lightness drifts along the second: nearby colours stay distinguishable.
  Eigen::Index longest = 0;
  extent.maxCoeff(&longest);
  const Eigen::Index second = (longest + 1) % 3, third = (longest + 2) % 3;
  const double hue = 0.78 * u[longest] + 0.12 * u[second];
  Eigen::Vector3d base = hue_colour(hue, 0.42, 0.95);
  base = base * (0.88 + 0.12 * u[third]);

  const double cell = extent.maxCoeff() / std::max(cells, 1);
  const Eigen::Vector3d g = (p - box_min) / cell;
  const long parity = static_cast<long>(std::floor(g.x())) + static_cast<long>(std::floor(g.y())) +
                      static_cast<long>(std::floor(g.z()));
  return (parity & 1) ? Eigen::Vector3d(base * (1.0 - contrast)) : base;
}

CheckerTexture make_checker_texture(const Eigen::MatrixXd& V, int cells) {
  if (V.rows() == 0 || V.cols() != 3) throw InvalidInputError("make_checker_texture: V must be non-empty #V by 3");
  CheckerTexture texture;
  texture.box_min = V.colwise().minCoeff().transpose();
  texture.box_max = V.colwise().maxCoeff().transpose();
  texture.cells = cells;
  return texture;
}

Eigen::MatrixXd evaluate_texture(const CheckerTexture& texture, const Eigen::MatrixXd& P) {
  Eigen::MatrixXd C(P.rows(), 3);
  for (Eigen::Index i = 0; i < P.rows(); ++i) C.row(i) = texture(P.row(i).transpose()).transpose();
  return C;
}

Eigen::Vector3d sequential_colour(double t) {
  // Control points sampled by eye along a viridis-like path; linear interpolation between them.
  static constexpr std::array<std::array<double, 3>, 6> kStops = {{{0.267, 0.005, 0.329},
                                                                   {0.255, 0.267, 0.529},
                                                                   {0.165, 0.471, 0.557},
                                                                   {0.133, 0.659, 0.518},
                                                                   {0.478, 0.820, 0.318},
                                                                   {0.993, 0.906, 0.144}}};
  t = std::clamp(std::isfinite(t) ? t : 1.0, 0.0, 1.0) * (kStops.size() - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(t), kStops.size() - 2);
  const double s = t - i;
  Eigen::Vector3d c;
  for (int k = 0; k < 3; ++k) c[k] = (1.0 - s) * kStops[i][k] + s * kStops[i + 1][k];
  return c;
}

Eigen::MatrixXd sequential_colours(const Eigen::VectorXd& values, double lo, double hi) {
  Eigen::MatrixXd C(values.size(), 3);
  const double range = hi > lo ? hi - lo : 1.0;
  for (Eigen::Index i = 0; i < values.size(); ++i) C.row(i) = sequential_colour((values[i] - lo) / range).transpose();
  return C;
}

Eigen::MatrixXd landmark_colours(int n) {
  static constexpr std::array<std::array<double, 3>, 12> kPalette = {{{0.89, 0.10, 0.11},
                                                                      {0.22, 0.49, 0.72},
                                                                      {1.00, 0.50, 0.00},
                                                                      {0.60, 0.31, 0.64},
                                                                      {1.00, 0.85, 0.10},
                                                                      {0.00, 0.75, 0.80},
                                                                      {0.97, 0.51, 0.75},
                                                                      {0.65, 0.34, 0.16},
                                                                      {0.20, 0.20, 0.75},
                                                                      {0.00, 0.35, 0.40},
                                                                      {0.80, 0.00, 0.45},
                                                                      {0.45, 0.45, 0.45}}};
  Eigen::MatrixXd C(std::max(n, 0), 3);
  for (int i = 0; i < n; ++i) {
    if (i < static_cast<int>(kPalette.size())) {
      C.row(i) << kPalette[i][0], kPalette[i][1], kPalette[i][2];
    } else {
      const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
      C.row(i) = hue_colour(i * golden, 0.1, 0.95).transpose();
    }
  }
  return C;
}

}  // namespace liftmap
