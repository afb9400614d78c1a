#pragma once
/// Landmarks on surface points made vertices of the refined mesh before the cut paths are traced, so that the
/// cut tree runs through them and the map interpolates them exactly (paper §3.4: the tree connects the landmarks,
/// which must be vertices).

#include <vector>

#include "core/mesh.h"
#include "core/surface_point.h"
#include "cut/refined_mesh.h"

namespace liftmap {

/// Makes every landmark a vertex of `refined`: a vertex landmark is its input vertex; an edge or face landmark
/// becomes a new vertex at its exact position (interpolated from the input vertices), and the input faces holding
/// new vertices are re-triangulated (remesh_along_paths). Input vertex i stays refined vertex i.
/// \param refined the trivial refinement of `input` (make_refined_mesh), refined in place
/// \param input the input mesh
/// \param landmarks points of `input`; a face point with a zero barycentric coordinate is located on its edge or
///        vertex first (canonical_point)
/// \return the refined vertex of each landmark
/// \throw InvalidInputError if a new vertex would be at the point of another landmark or of an input vertex (too
///        close to tell apart in the plane of its face).
std::vector<int> insert_landmarks(RefinedMesh& refined, const Mesh& input, const std::vector<SurfacePoint>& landmarks);

}  // namespace liftmap
