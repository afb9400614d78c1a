#pragma once
/// Exact check of local injectivity of a flattening, the condition under which path lifting is well defined
/// (paper §3.2, footnote 1 and "Sufficient conditions"; docs/algorithm.md, "Facts the tests check").

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/mesh.h"

namespace liftmap {

/// What `check_local_injectivity` found. A flattening is locally injective iff all three lists are empty.
struct LocalInjectivityReport {
  std::vector<FaceId> flipped_faces;            ///< faces that are clockwise or degenerate in the flattening
  std::vector<VertexId> bad_interior_vertices;  ///< interior vertices whose one-ring winds != 1 time around them
  std::vector<VertexId> bad_boundary_vertices;  ///< boundary vertices whose angle sum is >= 2*pi

  [[nodiscard]] bool locally_injective() const {
    return flipped_faces.empty() && bad_interior_vertices.empty() && bad_boundary_vertices.empty();
  }
  /// One line naming the first offending elements with their coordinates; empty if locally injective.
  [[nodiscard]] std::string summary(const Eigen::MatrixXd& X) const;
};

/// Checks that the flattening `X` of `mesh` is injective on every one-ring: every face is counter-clockwise,
/// the faces around every interior vertex wind exactly once around it (angle sum 2*pi, no branch point), and
/// the faces around every boundary vertex sweep an angle < 2*pi. All decisions use exact orientation
/// predicates; with every face counter-clockwise, the winding is counted exactly as the number of times the
/// fan sweeps past the direction of its first edge.
/// \param mesh any manifold mesh; isolated vertices are ignored
/// \param X #V by 2 flattening
/// \throw InvalidInputError if `X` does not have #V rows and 2 columns
LocalInjectivityReport check_local_injectivity(const Mesh& mesh, const Eigen::MatrixXd& X);

}  // namespace liftmap
