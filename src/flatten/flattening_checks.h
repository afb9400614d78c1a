#pragma once
/// Liftability checks of a flattening (paper §3.3, "Liftability"; docs/algorithm.md, "Facts the tests check").

#include <Eigen/Core>

#include "core/mesh.h"

namespace liftmap {

/// Twice the signed area of each flattened face (positive: orientation preserved).
/// \param F #F by 3 vertex indices; \param U #V by 2 positions \return #F values
Eigen::VectorXd signed_double_areas(const Eigen::MatrixXi& F, const Eigen::MatrixXd& U);

/// Sum of the flattened corner angles at each vertex (unsigned angles in [0, pi]); 2 pi at interior vertices
/// and below 2 pi at boundary vertices of a locally injective flattening with positive faces.
/// \param U #V by 2 positions \return #V angle sums (0 for isolated vertices)
Eigen::VectorXd angle_sums(const Mesh& mesh, const Eigen::MatrixXd& U);

}  // namespace liftmap
