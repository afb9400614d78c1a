#pragma once
/// The feasible start of the joint flattening (paper §3.3, "Initialization"), without the exponential squeeze of
/// parts no cut enters.
///
/// The paper starts from a Tutte embedding of each disk with its boundary on a convex curve. A part of the surface
/// that no cut path enters (a tail, an ear, a finger without a landmark) is a capped tube hanging off the disk's
/// interior, and a harmonic embedding shrinks a tube of length L and girth C like exp(-2 pi L / C) in length: at
/// L / C = 4 the tip's faces underflow double precision, and long before that the first convex subproblems crawl
/// through distortions of 1e6-1e13. Where plain mean-value Tutte squeezes a face's area below min_relative_area of
/// its share of the surface's, the start is instead a convex-combination map whose weights drift towards the boundary
/// (TutteWeights::drift, depth = edge-graph distance from the boundary): still bijective in exact arithmetic, with the
/// same boundary, and along a tube the drift offsets the ring's inward pull that makes the harmonic map shrink it. Each
/// drift is tried everywhere and only where plain Tutte squeezes (TutteWeights::drift_scale); the disk keeps the
/// embedding of lowest flattening energy. docs/algorithm.md has the derivation and the measurements.

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "core/mesh.h"

namespace liftmap {

/// When and which drifts are tried.
struct FlatteningStartOptions {
  /// Plain mean-value Tutte is kept if no face's share of the planar area is below this fraction of its share of
  /// the surface's area (faces that are small on the surface too, such as the cut's slivers, are not squeezed).
  double min_relative_area = 1e-4;
  /// TutteWeights::drift values tried, each localised and everywhere (two solves each); which ones shapes choose is
  /// in docs/performance.md ("A map in seconds").
  std::vector<double> drifts{0.5, 1, 2, 3, 4};
};

/// One embedding tried.
struct FlatteningStartCandidate {
  double drift = 0;           ///< TutteWeights::drift (0: plain mean-value Tutte)
  bool local = false;         ///< drift only where plain Tutte squeezes (TutteWeights::drift_scale)
  double energy = 0;          ///< the caller's energy of the embedding; +inf if a face is flipped or degenerate
  double min_area_ratio = 0;  ///< smallest face area over the mean face area (<= 0: flipped or degenerate)
};

/// The start of one disk.
struct FlatteningStart {
  Eigen::MatrixXd U;                ///< #V by 2 positions, boundary vertices at B
  FlatteningStartCandidate chosen;  ///< U's drift, energy and smallest face area
  bool squeezed = false;            ///< plain Tutte squeezed a face below min_relative_area (drifts were tried)
  std::vector<FlatteningStartCandidate> candidates;  ///< every embedding tried: plain Tutte first
};

/// Computes the start of one disk with the given boundary positions: plain mean-value Tutte, or, if that squeezes
/// a face below options.min_relative_area, the drifted convex-combination map of lowest energy (plain Tutte included).
/// \param mesh a disk; \param V #V by 3 positions; \param boundary its boundary loop in order
/// \param B #boundary by 2 positions on a convex curve
/// \param energy the flattening energy of #V by 2 positions (only called on embeddings with positive faces)
/// \throw InvalidInputError as tutte_embedding(); PipelineError if no embedding tried has only positive faces.
FlatteningStart flattening_start(const Mesh& mesh, const Eigen::MatrixXd& V, const std::vector<VertexId>& boundary,
                                 const Eigen::MatrixXd& B, const std::function<double(const Eigen::MatrixXd&)>& energy,
                                 const FlatteningStartOptions& options = {});

}  // namespace liftmap
