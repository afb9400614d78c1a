#pragma once
/// distortion.png: an area-weighted histogram of per-face distortion with its mean marked, as in the paper's
/// Figure 9.

#include <Eigen/Core>
#include <string>

#include "render/image.h"

namespace liftmap {

/// Size, binning and labels of the histogram.
struct HistogramOptions {
  int width = 900;
  int height = 560;
  int bins = 40;
  double x_min = 1.0;  ///< left end of the x axis (distortion is >= 1)
  /// Right end of the x axis; 0: chosen from the data (the 99th weighted percentile, at least the mean, rounded
  /// up to a round number). Values beyond it are counted in the last bin.
  double x_max = 0.0;
  std::string title = "distortion of f";
  std::string x_label = "distortion max(S, 1/s)";
  std::string y_label = "% of area";
  Eigen::Vector3d bar_colour{0.30, 0.50, 0.75};
  Eigen::Vector3d mean_colour{0.85, 0.12, 0.12};
  Eigen::Vector3d background{1.0, 1.0, 1.0};
};

/// Draws the histogram: bars of the fraction of total weight per bin, x axis with tick labels, y axis in percent
/// of the total weight, a vertical line at the weighted mean with its value written next to it.
/// \param values #N per-face values (non-finite values count in the last bin)
/// \param weights #N non-negative weights (face areas), or empty for equal weights
/// \throw InvalidInputError for mismatched sizes, negative weights, zero total weight, or a non-positive size
Image render_histogram(const Eigen::VectorXd& values, const Eigen::VectorXd& weights,
                       const HistogramOptions& options = {});

/// render_histogram written as a PNG.
/// \throw as render_histogram; IoError if the file cannot be written
void render_histogram_png(const Eigen::VectorXd& values, const Eigen::VectorXd& weights, const std::string& path,
                          const HistogramOptions& options = {});

}  // namespace liftmap
