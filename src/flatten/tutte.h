#pragma once
/// Tutte embedding with mean-value weights (Floater 2003), the feasible start of the joint flattening
/// (paper §3.3, "Initialization").

#include <Eigen/Core>
#include <vector>

#include "core/mesh.h"

namespace liftmap {

/// Embeds a disk in the plane: boundary vertices are pinned, every interior vertex is the mean-value-weighted
/// average of its neighbours. With the boundary on a convex polygon the result is bijective.
/// \param mesh a disk (one boundary loop)
/// \param V #V by 3 vertex positions
/// \param boundary the boundary loop's vertices in order
/// \param B #boundary by 2 positions of those vertices
/// \return #V by 2 positions
/// \throw InvalidInputError if the mesh is not a disk or the sizes disagree; PipelineError if the solve fails.
Eigen::MatrixXd tutte_embedding(const Mesh& mesh, const Eigen::MatrixXd& V, const std::vector<VertexId>& boundary,
                                const Eigen::MatrixXd& B);

}  // namespace liftmap
