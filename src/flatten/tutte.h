#pragma once
/// Tutte embedding with mean-value weights (Floater 2003), the feasible start of the joint flattening
/// (paper §3.3, "Initialization").

#include <Eigen/Core>
#include <vector>

#include "core/mesh.h"

namespace liftmap {

/// Weights of the convex combinations: the mean-value weight w_ij of each edge (Floater 2003), times
/// exp(drift * c_i * (depth_i - depth_j) / |x_i - x_j|) with c_i = drift_scale[i] (1 if drift_scale is empty). With
/// depth a distance along edges the exponent lies in [-drift c_i, drift c_i]: a vertex weighs its shallower
/// neighbours more. In a tube along which the depth grows (a part of the disk no cut enters), the average of a
/// ring pulls each vertex inwards, and a harmonic map shrinks the tube like exp(-2 pi L / C) in length (L its
/// length, C its girth); the drift offsets that pull, so the rings' radii fall far more slowly towards the tip.
/// The weights stay positive, so the embedding stays a convex-combination map (asymmetric weights included).
struct TutteWeights {
  std::vector<double> depth;        ///< #V values, e.g. distances from the boundary; empty: no drift
  double drift = 0;                 ///< finite; 0: plain mean-value weights
  std::vector<double> drift_scale;  ///< #V values in [0, 1], or empty (1 everywhere)
};

/// Embeds a disk in the plane: boundary vertices are pinned, every interior vertex is the weighted average of its
/// neighbours (TutteWeights). With the boundary on a convex polygon and positive
/// weights the result is bijective in exact arithmetic (Floater 2003).
/// \param mesh a disk (one boundary loop)
/// \param V #V by 3 vertex positions
/// \param boundary the boundary loop's vertices in order
/// \param B #boundary by 2 positions of those vertices
/// \param weights the scaling of the mean-value weights (default: none)
/// \return #V by 2 positions
/// \throw InvalidInputError if the mesh is not a disk or the sizes disagree; PipelineError if the solve fails.
Eigen::MatrixXd tutte_embedding(const Mesh& mesh, const Eigen::MatrixXd& V, const std::vector<VertexId>& boundary,
                                const Eigen::MatrixXd& B, const TutteWeights& weights = {});

/// tutte_embedding() for several sets of weights at once (one sparsity analysis for all).
/// \return one #V by 2 embedding per set of weights, in their order
std::vector<Eigen::MatrixXd> tutte_embeddings(const Mesh& mesh, const Eigen::MatrixXd& V,
                                              const std::vector<VertexId>& boundary, const Eigen::MatrixXd& B,
                                              const std::vector<TutteWeights>& weights);

}  // namespace liftmap
