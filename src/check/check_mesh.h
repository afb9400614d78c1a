#pragma once
/// Mesh validation: topology, geometry and the conditions the mapping pipeline needs.

#include <Eigen/Core>
#include <nlohmann/json_fwd.hpp>
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
  int n_components = 0;                 ///< connected components of the faces
  int n_boundary_edges = 0;             ///< edges with only one face
  std::optional<int> n_boundary_loops;  ///< only for a manifold, oriented mesh (loops are undefined otherwise)
  int euler_characteristic = 0;         ///< V - E + F, unreferenced vertices not counted
  std::optional<int> genus;             ///< only for a manifold, oriented mesh
  std::vector<MeshProblem> problems;    ///< everything that prevents mapping; empty means mappable

  /// True if liftmap can map this mesh: closed, connected, manifold, consistently oriented with outward normals,
  /// genus 0, finite coordinates within CoordinateLimits, no degenerate, duplicate or unreferenced elements.
  [[nodiscard]] bool mappable() const { return problems.empty(); }
  /// One line summarising why the mesh cannot be mapped (first examples of every problem); empty if mappable.
  [[nodiscard]] std::string summary() const;
};

/// Coordinate ranges the mapping pipeline computes with; check_mesh reports a mesh outside them (README,
/// "Command line"). They keep squared lengths and areas far from overflow and underflow and leave enough digits
/// for the shape after the pipeline subtracts nearby positions.
struct CoordinateLimits {
  static constexpr double kMaxMagnitude = 1e30;  ///< every |coordinate| at most this
  static constexpr double kMinDiagonal = 1e-30;  ///< the bounding box diagonal at least this
  static constexpr double kMaxOffset = 1e4;      ///< max |coordinate| at most this times the diagonal
  static constexpr double kMinEdgeRatio = 1e-8;  ///< every edge at least this times the diagonal
};

/// Checks a triangle mesh: everything that prevents mapping it, including an inside-out orientation (a closed
/// mesh whose signed volume is negative) and coordinates outside CoordinateLimits. check_mesh is the one
/// validation of `liftmap check` and of map_meshes: a mesh it finds mappable is one the pipeline accepts.
/// \param V #V by 3 positions
/// \param F #F by 3 vertex indices (out-of-range indices are reported, not assumed away)
MeshReport check_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

/// The volume a closed, consistently oriented mesh encloses, positive when its faces are counter-clockwise seen
/// from outside (normals outward), negative for an inside-out mesh. Meaningless for an open mesh.
/// \param V #V by 3 positions; \param F #F by 3 faces, indices in range
double signed_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

/// The report as JSON, as `liftmap check --json` prints it per mesh: counts, topology, "mappable" and "problems"
/// (kind, count, examples naming the elements); undefined counts (boundary loops, genus of a non-manifold) are null.
/// \param name the mesh's file name or another label, stored as "mesh"
nlohmann::json mesh_report_json(const MeshReport& report, const std::string& name);

/// Reverses the faces of a closed mesh whose signed volume is negative (inside-out), so that its normals point
/// outward (`liftmap map --fix-orientation`). Meshes with out-of-range indices or non-finite coordinates are left
/// to check_mesh and never reversed.
/// \param F #F by 3 faces, columns 1 and 2 swapped if reversed
/// \return the signed volume before the reversal if the faces were reversed, nullopt otherwise
std::optional<double> reverse_if_inside_out(const Eigen::MatrixXd& V, Eigen::MatrixXi& F);

/// Throws InvalidInputError("<path>: <summary>") unless the mesh is mappable.
void require_mappable(const MeshReport& report, const std::string& path);

}  // namespace liftmap
