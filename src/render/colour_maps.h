#pragma once
/// Colour functions that make a map readable: a solid texture of the source mesh (smooth colour by position with
/// a 3D checkerboard on top), a sequential colour map for scalar fields, and distinct colours for landmarks.

#include <Eigen/Core>

namespace liftmap {

/// A solid texture over a bounding box: the hue varies smoothly with the position in the box (so that far-apart
/// regions differ), and a 3D checkerboard of cubes with `cells` cubes along the longest side of the box darkens
/// every other cube (so that stretch and shear show as deformed squares).
struct CheckerTexture {
  Eigen::Vector3d box_min = Eigen::Vector3d::Zero();
  Eigen::Vector3d box_max = Eigen::Vector3d::Ones();
  int cells = 14;         ///< checkerboard cubes along the longest side of the box
  double contrast = 0.3;  ///< how much darker the dark cubes are, in [0,1)

  /// RGB in [0,1] at point p (points outside the box are clamped for the hue, the checkerboard continues).
  Eigen::Vector3d operator()(const Eigen::Vector3d& p) const;
};

/// The checker texture spanning the bounding box of V (#V by 3).
/// \throw InvalidInputError for an empty V
CheckerTexture make_checker_texture(const Eigen::MatrixXd& V, int cells = 14);

/// The texture evaluated at every row of P (#P by 3): #P by 3 per-vertex colours, e.g. colour_A(g(y)) for B's
/// vertices y when P holds their images g(y) on A.
Eigen::MatrixXd evaluate_texture(const CheckerTexture& texture, const Eigen::MatrixXd& P);

/// A sequential, perceptually ordered colour map (dark blue through teal and green to yellow, viridis-like):
/// t in [0,1] (clamped) to RGB in [0,1].
Eigen::Vector3d sequential_colour(double t);

/// Per-element colours of a scalar field: values mapped linearly from [lo, hi] onto sequential_colour.
/// \param values #N values
/// \return #N by 3 RGB
Eigen::MatrixXd sequential_colours(const Eigen::VectorXd& values, double lo, double hi);

/// n distinct, saturated colours for landmarks (a fixed palette of 12, then golden-angle hues): landmark i gets
/// row i on both meshes.
/// \return n by 3 RGB
Eigen::MatrixXd landmark_colours(int n);

}  // namespace liftmap
