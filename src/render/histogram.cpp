#include "render/histogram.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/errors.h"
#include "render/text.h"

namespace liftmap {
namespace {

/// A round tick step (1, 2, 2.5 or 5 times a power of ten) giving about `target` intervals over `range`.
double tick_step(double range, int target) {
  const double raw = range / target;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * power >= raw) return m * power;
  return 10.0 * power;
}

/// x with as many decimals as the tick step needs (2.5 -> 1, 0.25 -> 2, 5 -> 0).
std::string format_number(double x, double step) {
  int decimals = 0;
  for (double scaled = step; decimals < 6 && std::abs(scaled - std::round(scaled)) > 1e-6 * scaled; scaled *= 10.0)
    ++decimals;
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, x);
  return buffer;
}

/// Weighted quantile of the finite values: the smallest value with at least q of the weight at or below it.
double weighted_quantile(const Eigen::VectorXd& values, const Eigen::VectorXd& weights, double q) {
  std::vector<Eigen::Index> order;
  for (Eigen::Index i = 0; i < values.size(); ++i)
    if (std::isfinite(values[i])) order.push_back(i);
  if (order.empty()) return 1.0;
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return values[a] < values[b]; });
  double total = 0;
  for (const Eigen::Index i : order) total += weights[i];
  double sum = 0;
  for (const Eigen::Index i : order) {
    sum += weights[i];
    if (sum >= q * total) return values[i];
  }
  return values[order.back()];
}

void vertical_line(Image& image, int x, int y0, int y1, int thickness, const Eigen::Vector3d& c) {
  fill_rect(image, x - thickness / 2, std::min(y0, y1), x - thickness / 2 + thickness, std::max(y0, y1) + 1, c);
}

void horizontal_line(Image& image, int x0, int x1, int y, int thickness, const Eigen::Vector3d& c) {
  fill_rect(image, std::min(x0, x1), y - thickness / 2, std::max(x0, x1) + 1, y - thickness / 2 + thickness, c);
}

}  // namespace

Image render_histogram(const Eigen::VectorXd& values, const Eigen::VectorXd& weights_in,
                       const HistogramOptions& options) {
  if (options.width < 200 || options.height < 150 || options.bins < 1)
    throw InvalidInputError("render_histogram: the image must be at least 200 by 150 with at least one bin");
  const Eigen::VectorXd weights = weights_in.size() == 0 ? Eigen::VectorXd::Ones(values.size()) : weights_in;
  if (weights.size() != values.size())
    throw InvalidInputError("render_histogram: " + std::to_string(values.size()) + " values but " +
                            std::to_string(weights.size()) + " weights");
  if (values.size() == 0) throw InvalidInputError("render_histogram: no values");
  if ((weights.array() < 0).any() || !weights.allFinite())
    throw InvalidInputError("render_histogram: weights must be finite and non-negative");
  const double total = weights.sum();
  if (!(total > 0)) throw InvalidInputError("render_histogram: the weights sum to zero");

  double finite_weight = 0, weighted_sum = 0;
  for (Eigen::Index i = 0; i < values.size(); ++i)
    if (std::isfinite(values[i])) {
      finite_weight += weights[i];
      weighted_sum += weights[i] * values[i];
    }
  const double mean = finite_weight > 0 ? weighted_sum / finite_weight : options.x_min;

  const double x_min = options.x_min;
  double x_max = options.x_max;
  if (!(x_max > x_min)) {
    const double hi = std::max({weighted_quantile(values, weights, 0.99), mean * 1.05, x_min + 0.05});
    const double step = tick_step(hi - x_min, 5);
    x_max = x_min + std::ceil((hi - x_min) / step - 1e-9) * step;
  }
  const double x_step = tick_step(x_max - x_min, 8);

  std::vector<double> fraction(options.bins, 0.0);
  double above = 0;
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    const double v = values[i];
    int bin = options.bins - 1;
    if (std::isfinite(v) && v < x_max)
      bin = std::max(0, static_cast<int>((v - x_min) / (x_max - x_min) * options.bins));
    if (!std::isfinite(v) || v > x_max) above += weights[i];
    fraction[std::min(bin, options.bins - 1)] += weights[i] / total;
  }
  const double y_top = std::max(1e-9, *std::max_element(fraction.begin(), fraction.end())) * 100.0 * 1.12;
  const double y_step = tick_step(y_top, 5);
  const double y_max = std::min(100.0, std::ceil(y_top / y_step - 1e-9) * y_step);

  const int s = 2;  // font scale
  const int left = 30 + text_width("00.0", s) + 14, right = options.width - 30;
  const int top = 24 + 3 * kTextHeight * s, bottom = options.height - 30 - 2 * kTextHeight * s - 10;
  auto to_x = [&](double x) {
    return left + static_cast<int>(std::lround((x - x_min) / (x_max - x_min) * (right - left)));
  };
  auto to_y = [&](double pct) { return bottom - static_cast<int>(std::lround(pct / y_max * (bottom - top))); };

  Image image(options.width, options.height, options.background);
  const Eigen::Vector3d ink(0.15, 0.15, 0.15), grid(0.88, 0.88, 0.88);
  for (double t = y_step; t <= y_max + 1e-9 * y_max; t += y_step) horizontal_line(image, left, right, to_y(t), 1, grid);

  const Eigen::Vector3d edge = 0.7 * options.bar_colour;
  for (int b = 0; b < options.bins; ++b) {
    if (fraction[b] <= 0) continue;
    const int x0 = to_x(x_min + (x_max - x_min) * b / options.bins);
    const int x1 = to_x(x_min + (x_max - x_min) * (b + 1) / options.bins);
    const int y = std::min(to_y(fraction[b] * 100.0), bottom - 1);
    fill_rect(image, x0, y, x1 + 1, bottom, edge);
    fill_rect(image, x0 + 1, y + 1, x1, bottom, options.bar_colour);
  }

  // Axes, ticks and tick labels.
  horizontal_line(image, left, right, bottom, 2, ink);
  vertical_line(image, left, top, bottom, 2, ink);
  const int glyph_h = kTextAscent * s;
  for (double t = x_min; t <= x_max + 1e-9 * x_max; t += x_step) {
    const int x = to_x(t);
    vertical_line(image, x, bottom, bottom + 6, 2, ink);
    const std::string label = format_number(t, x_step);
    draw_text(image, x - text_width(label, s) / 2, bottom + 12, label, ink, s);
  }
  for (double t = 0; t <= y_max + 1e-9 * y_max; t += y_step) {
    const int y = to_y(t);
    horizontal_line(image, left - 6, left, y, 2, ink);
    const std::string label = format_number(t, y_step);
    draw_text(image, left - 12 - text_width(label, s), y - glyph_h / 2, label, ink, s);
  }

  // The mean: a vertical line with its value, written on the side with more room.
  const int mx = to_x(std::clamp(mean, x_min, x_max));
  vertical_line(image, mx, top, bottom, 3, options.mean_colour);
  char mean_text[64];
  std::snprintf(mean_text, sizeof mean_text, "mean %.3f", mean);
  const int mean_w = text_width(mean_text, s);
  const int mean_x = mx + 8 + mean_w <= right ? mx + 8 : mx - 8 - mean_w;
  fill_rect(image, mean_x - 3, top + 2, mean_x + mean_w + 3, top + 6 + glyph_h, options.background);
  draw_text(image, mean_x, top + 4, mean_text, options.mean_colour, s);
  if (above > 0) {
    char above_text[64];
    std::snprintf(above_text, sizeof above_text, "%.1f%% above %s (last bar)", 100.0 * above / total,
                  format_number(x_max, x_step).c_str());
    draw_text(image, right - text_width(above_text, s), top + 10 + glyph_h, above_text, ink, s);
  }

  // Title, axis labels.
  draw_text(image, (left + right - text_width(options.title, s + 1)) / 2, 12, options.title, ink, s + 1);
  draw_text(image, (left + right - text_width(options.x_label, s)) / 2, options.height - 16 - glyph_h, options.x_label,
            ink, s);
  draw_text(image, left - text_width(options.y_label, s) / 2 < 4 ? 4 : left - text_width(options.y_label, s) / 2,
            top - glyph_h - 14, options.y_label, ink, s);
  return image;
}

void render_histogram_png(const Eigen::VectorXd& values, const Eigen::VectorXd& weights, const std::string& path,
                          const HistogramOptions& options) {
  write_png(path, render_histogram(values, weights, options));
}

}  // namespace liftmap
