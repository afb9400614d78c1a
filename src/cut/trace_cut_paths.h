#pragma once
/// Tracing the cut tree on both meshes with consistent embeddings (paper §3.4).

#include <array>
#include <vector>

#include "core/mesh.h"
#include "cut/refined_mesh.h"

namespace liftmap {

/// Options of `trace_cut_paths`.
struct TraceOptions {
  bool steiner = true;  ///< search paths across faces (Steiner points on edges) instead of along edges only
  bool shorten = true;  ///< straighten each path toward a geodesic (`shorten_path`)
};

/// The tree paths on both meshes.
struct TracedPaths {
  std::vector<std::array<int, 2>> edges;           ///< tree edges {parent, child} (landmark indices), tracing order
  std::vector<std::vector<int>> paths_a, paths_b;  ///< per edge, refined vertex ids from child to parent landmark
};

/// Traces the tree edges one after the other, each on the surface already cut by the earlier ones, so that the
/// two embeddings are consistent by construction: every path is simple, runs along refined edges, touches the
/// earlier paths only at its parent landmark, passes through no other landmark, and enters the parent landmark
/// in the same sector (between the same two earlier paths) on both meshes, the sector minimising the sum of the
/// two path lengths. Before each path, edges that could disconnect the remaining surface are split (edges between
/// two tree vertices, between two landmarks, between a landmark not yet in the tree and the tree), which
/// guarantees that every sector is reachable.
/// \param a, b refined meshes of the closed genus-0 inputs, refined in place
/// \param input_a, input_b the input meshes (provenance of new vertices)
/// \param landmarks_a, landmarks_b distinct refined vertex ids, landmark i of A corresponds to landmark i of B
/// \param tree k - 1 edges {parent, child}, each parent already in the tree when its edge comes (see
///        `minimum_spanning_tree`)
/// \throw PipelineError if an internal invariant fails (a sector cannot be reached).
TracedPaths trace_cut_paths(RefinedMesh& a, const Mesh& input_a, const std::vector<int>& landmarks_a, RefinedMesh& b,
                            const Mesh& input_b, const std::vector<int>& landmarks_b,
                            const std::vector<std::array<int, 2>>& tree, const TraceOptions& options = {});

}  // namespace liftmap
