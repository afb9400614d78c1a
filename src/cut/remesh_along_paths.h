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
  int straightened_vertices = 0;      ///< path vertices inside an input face dropped: the path runs straight across it
  int dropped_vertices = 0;           ///< refined vertices on no path (left by earlier re-triangulations), removed
  int remeshed_faces = 0;             ///< input faces re-triangulated (the others are the input face itself)
  bool straightening_failed = false;  ///< straightened paths touched in a face (rounding) or met a landmark in another
                                      ///< cyclic order than traced: kept as traced instead
  bool kept_as_traced = false;  ///< a face could not be re-triangulated (two vertices at one point): nothing changed
  int exact_faces = 0;          ///< of those, faces triangulated again with exact constructions after rounding failed
};

/// If `straighten`, straightens each path across the input faces first (a path vertex inside an input face whose
/// path neighbours lie on that face is dropped, as long as the path keeps two edges; if rounding makes two straightened
/// paths touch, or the paths leave a vertex where they meet in another cyclic order than traced, which would change
/// the tree's embedding on this mesh only, the paths are kept as traced). Rebuilds `refined` so that it holds only the
/// input vertices and the vertices of `paths`, and triangulates each input face that holds a path vertex as the
/// constrained Delaunay triangulation (in the plane of the face) of its three corners, the path vertices on its sides
/// and inside it, with every path segment that crosses it as a constraint. Vertices keep their positions and their
/// exact provenance (`RefinedMesh::on_input`); every refined face lies inside one input face, so the refined surface
/// is still the input surface. Replaces the ear clipping of the repeated insertions during tracing, whose caps and
/// slivers carried the flattenings' largest distortions, and removes the vertices of abandoned intermediate paths.
/// \param refined a refinement of `input` whose first `input.n_vertices()` vertices are the input vertices
/// \param input the input mesh
/// \param paths per tree edge, refined vertex ids; renumbered in place to the new refined mesh
/// \param straighten drop path vertices inside input faces (not after `equalize_paths`, whose paired vertex
///        counts it would change)
/// \return what was changed
/// If a face cannot be re-triangulated (two of its vertices at one point, a path segment in no input face, a
/// triangulation that misses a path segment or does not tile the face), `refined` and `paths` are left as they are
/// (a valid refinement, only not re-triangulated) and `kept_as_traced` is set.
RemeshStats remesh_along_paths(RefinedMesh& refined, const Mesh& input, std::vector<std::vector<int>>& paths,
                               bool straighten = false);

}  // namespace liftmap
