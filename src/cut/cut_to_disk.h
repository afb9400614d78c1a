#pragma once
/// Cutting a closed mesh along a tree of edges into a disk (paper §3.4: "adjacent triangles sharing an edge on
/// the geodesic are separated, and their two shared vertices are duplicated").

#include <Eigen/Core>
#include <vector>

#include "core/mesh.h"

namespace liftmap {

/// A mesh cut open along some of its edges.
struct CutDisk {
  Eigen::MatrixXi F;           ///< #F by 3 faces of the cut mesh; face i is face i of the uncut mesh
  Eigen::VectorXi to_refined;  ///< #Vc: for every cut-mesh vertex, the uncut vertex it is a copy of
};

/// Duplicates vertices so that the faces on the two sides of every cut edge no longer share it. A vertex with
/// j cut edges gets j copies (one if j <= 1); cutting a closed genus-0 mesh along a tree gives a disk.
/// \pre every cut edge has an end with at least two cut edges (true for a tree of two or more edges): a lone
///      cut edge cannot be opened in a simplicial mesh.
/// \param mesh the uncut mesh (closed)
/// \param is_cut per edge of `mesh`, non-zero if the mesh is cut along it
CutDisk cut_to_disk(const Mesh& mesh, const std::vector<char>& is_cut);

}  // namespace liftmap
