#include "exact_geodesic.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>

#include <string>

#include "core/errors.h"

namespace liftmap {

std::vector<double> exact_geodesic_distances(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int source,
                                             const std::vector<int>& targets) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
  using Traits = CGAL::Surface_mesh_shortest_path_traits<Kernel, SurfaceMesh>;
  using ShortestPath = CGAL::Surface_mesh_shortest_path<Traits>;
  using VertexIndex = SurfaceMesh::Vertex_index;

  SurfaceMesh mesh;
  std::vector<VertexIndex> vertex;
  vertex.reserve(static_cast<size_t>(V.rows()));
  for (int i = 0; i < V.rows(); ++i) vertex.push_back(mesh.add_vertex(Kernel::Point_3(V(i, 0), V(i, 1), V(i, 2))));
  for (int f = 0; f < F.rows(); ++f) {
    const auto face = mesh.add_face(vertex[static_cast<size_t>(F(f, 0))], vertex[static_cast<size_t>(F(f, 1))],
                                    vertex[static_cast<size_t>(F(f, 2))]);
    if (face == SurfaceMesh::null_face()) {
      throw InvalidInputError("exact geodesics: face " + std::to_string(f) + " cannot be added (non-manifold mesh)");
    }
  }
  ShortestPath shortest(mesh);
  shortest.add_source_point(vertex[static_cast<size_t>(source)]);
  shortest.build_sequence_tree();
  std::vector<double> out;
  out.reserve(targets.size());
  for (const int t : targets)
    out.push_back(shortest.shortest_distance_to_source_points(vertex[static_cast<size_t>(t)]).first);
  return out;
}

}  // namespace liftmap
