#pragma once
/// Exact geodesic distances (CGAL's Surface_mesh_shortest_path, Xin-Wang): the reference against which the
/// fast paths are tested. About 0.7 s per source on a 10k-vertex mesh.

#include <Eigen/Core>
#include <vector>

namespace liftmap {

/// Exact geodesic distances on the surface from vertex `source` to each vertex of `targets`.
/// \param V #V by 3 positions
/// \param F #F by 3 faces of a closed or bordered manifold triangle mesh
/// \throw InvalidInputError if CGAL cannot build the mesh from F.
std::vector<double> exact_geodesic_distances(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int source,
                                             const std::vector<int>& targets);

}  // namespace liftmap
