#pragma once
/// Straightening an edge path on a refined mesh toward a geodesic (paper §3.4 cuts along geodesics).

#include <functional>
#include <vector>

#include "core/mesh.h"
#include "cut/refined_mesh.h"

namespace liftmap {

/// One straightening step: replaces `path` by the shortest path inside the strip of faces along one of its
/// sides (the side with the larger gain), computed by unfolding the strip and pulling the path taut (funnel
/// algorithm), and inserts the result into `refined` (splitting the crossed edges). The result never passes
/// through a blocked vertex: portals ending at one are shortened so that the path goes around it, at least 5% of
/// the crossed edge and 1% of the shortest edge of the input face it lies in away (where the edge is shorter than
/// that, the path keeps its own vertex at that edge's other end).
/// \param refined refined mesh, refined in place
/// \param input the input mesh (provenance of new vertices)
/// \param path refined vertex ids of a simple edge path with at least 2 vertices
/// \param blocked vertices the result must not pass through (its endpoints excepted)
/// \return the new path, refined vertex ids from the same start to the same end; never longer than `path`
std::vector<int> shorten_path(RefinedMesh& refined, const Mesh& input, const std::vector<int>& path,
                              const std::function<bool(int)>& blocked);

}  // namespace liftmap
