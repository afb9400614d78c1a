#pragma once
/// Mesh validation: topology, geometry and the conditions the mapping pipeline needs.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace liftmap {

/// One kind of problem found in a mesh, with a few named examples.
struct MeshProblem {
  std::string kind;                   ///< e.g. "non-manifold edge"
  int count = 0;                      ///< how many elements have it
  std::vector<std::string> examples;  ///< up to 5, each naming the element, e.g. "edge (12, 57) is shared by 3 faces"
};

/// What `check_mesh` found.
struct MeshReport {
  int n_vertices = 0;
  int n_faces = 0;
  int n_edges = 0;
  int n_components = 0;               ///< connected components of the faces
  int n_boundary_loops = 0;           ///< only when the mesh is manifold and oriented, else 0
  int euler_characteristic = 0;       ///< V - E + F, unreferenced vertices not counted
  std::optional<int> genus;           ///< only for a manifold, oriented mesh
  std::vector<MeshProblem> problems;  ///< everything that prevents mapping; empty means mappable

  /// True if liftmap can map this mesh: closed, connected, manifold, consistently oriented, genus 0, finite
  /// coordinates, no degenerate, duplicate or unreferenced elements.
  [[nodiscard]] bool mappable() const { return problems.empty(); }
  /// One line summarising why the mesh cannot be mapped (first examples of every problem); empty if mappable.
  [[nodiscard]] std::string summary() const;
};

/// Checks a triangle mesh.
/// \param V #V by 3 positions
/// \param F #F by 3 vertex indices (out-of-range indices are reported, not assumed away)
MeshReport check_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

/// Throws InvalidInputError("<path>: <summary>") unless the mesh is mappable.
void require_mappable(const MeshReport& report, const std::string& path);

}  // namespace liftmap
