#pragma once
/// The final triangulation of a refined mesh around its cut paths (paper §3.4, "remeshed accordingly so that the
/// geodesic passes through a connected set of edges"): every input face is re-triangulated from scratch as the
/// constrained Delaunay triangulation of its corners, the path vertices on it and the path segments across it.

#include <vector>

#include "core/mesh.h"
#include "cut/refined_mesh.h"

namespace liftmap {

/// Counts of a `remesh_along_paths` call.
struct RemeshStats {
  int dropped_vertices = 0;  ///< refined vertices on no path (left by earlier re-triangulations), removed
  int remeshed_faces = 0;    ///< input faces re-triangulated (the others are the input face itself)
  int exact_faces = 0;       ///< of those, faces triangulated again with exact constructions after rounding failed
};

/// Rebuilds `refined` so that it holds only the input vertices and the vertices of `paths`, and triangulates each
/// input face that holds a path vertex as the constrained Delaunay triangulation (in the plane of the face) of its
/// three corners, the path vertices on its sides and inside it, with every path segment that crosses it as a
/// constraint. Vertices keep their positions and their exact provenance (`RefinedMesh::on_input`); every refined
/// face lies inside one input face, so the refined surface is still the input surface. Replaces the ear clipping
/// of the repeated insertions during tracing, whose caps and slivers carried the flattenings' largest distortions,
/// and removes the vertices of abandoned intermediate paths.
/// \param refined a refinement of `input` whose first `input.n_vertices()` vertices are the input vertices
/// \param input the input mesh
/// \param paths per tree edge, refined vertex ids; renumbered in place to the new refined mesh
/// \return what was changed
/// \throw PipelineError if a path segment lies in no input face, or a face's triangulation misses a path segment
///        or does not tile the face (a bug; `refined` and `paths` are then unchanged).
RemeshStats remesh_along_paths(RefinedMesh& refined, const Mesh& input, std::vector<std::vector<int>>& paths);

}  // namespace liftmap
