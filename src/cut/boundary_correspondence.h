#pragma once
/// The boundary correspondence nu between the two cut disks (paper §3.4 and docs/algorithm.md): corresponding cut paths
/// are matched by the monotone cubic reparameterisation, each side's vertices are inserted into the other, and
/// nu pairs the boundary vertices one to one.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "core/mesh.h"
#include "cut/refined_mesh.h"

namespace liftmap {

/// r(s) = s + (L - l) (3 (s/l)^2 - 2 (s/l)^3): maps arc length s in [0, l] on the shorter path to arc length on
/// the longer one; r(0) = 0, r(l) = L, r'(0) = r'(l) = 1, monotone (docs/algorithm.md, "The boundary
/// reparameterisation"). \pre 0 < l <= L
double cubic_reparameterisation(double s, double l, double L);

/// The inverse of `cubic_reparameterisation`: the s in [0, l] with r(s) = y, y in [0, L].
double inverse_cubic_reparameterisation(double y, double l, double L);

/// Inserts vertices into corresponding paths so that `paths_a[e]` and `paths_b[e]` have equal vertex counts and
/// vertex j of one corresponds to vertex j of the other: the vertices of each path are mapped onto the other by
/// the cubic reparameterisation and inserted there, except where they come within `snap` of a local edge length
/// of an existing vertex, which is then paired with them instead (no sliver edges). The map is symmetric under
/// reversing both paths, so both sides of a cut path get the same correspondence. Arc lengths are measured in units
/// of the square root of each mesh's area (the flattening's normalisation), so that a mesh and a scaled copy of
/// it get the identity correspondence.
/// \param a, b refined meshes containing the paths, refined in place
/// \param paths_a, paths_b per tree edge, refined vertex ids of the path (same end landmarks on both meshes),
///        updated in place
/// \param snap fraction of the adjacent edge length within which a mapped vertex is paired with an existing one
void equalize_paths(RefinedMesh& a, const Mesh& input_a, std::vector<std::vector<int>>& paths_a, RefinedMesh& b,
                    const Mesh& input_b, std::vector<std::vector<int>>& paths_b, double snap = 0.1);

/// One cut disk as `match_boundaries` needs it.
struct CutBoundaryInput {
  const Mesh* cut = nullptr;                             ///< the cut mesh (a disk)
  const Eigen::VectorXi* to_refined = nullptr;           ///< #Vc: cut vertex -> refined vertex
  const std::vector<int>* landmarks = nullptr;           ///< k refined vertex ids of the landmarks
  const std::vector<std::vector<int>>* paths = nullptr;  ///< per tree edge, refined vertex ids of its path
};

/// nu: pairs {cut vertex of A, cut vertex of B} for every boundary vertex, in counter-clockwise boundary order
/// of A (and of B), starting at a landmark copy. Each side of each cut path on A is matched with the same side
/// of the same path on B.
/// \pre the paths were equalized (`equalize_paths`) before cutting.
/// \throw PipelineError if either mesh is not a disk or the boundaries do not correspond side by side.
std::vector<std::array<int, 2>> match_boundaries(const CutBoundaryInput& a, const CutBoundaryInput& b);

}  // namespace liftmap
