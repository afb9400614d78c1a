#pragma once
/// The files `liftmap map` and `liftmap cut` write (README, "Output files").

#include <Eigen/Core>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "core/surface_point.h"
#include "cut/cut_meshes.h"
#include "io/landmarks.h"
#include "io/read_mesh.h"
#include "map/map_meshes.h"

namespace liftmap {

/// Writes a vertex map: `#` header lines, then per source vertex `face b0 b1 b2` (face of the target mesh,
/// barycentric coordinates in the order of that face's vertices, full double precision).
/// \param images per source vertex, a face point of the target
/// \throw IoError if the file cannot be written
void write_vertex_map(const std::string& path, const std::vector<SurfacePoint>& images, const std::string& header);

/// Reads a vertex map written by write_vertex_map.
/// \param n_target_faces number of faces of the target mesh, to check indices
/// \throw IoError naming the file and line for a malformed line or an index out of range
std::vector<SurfacePoint> read_vertex_map(const std::string& path, int n_target_faces);

/// Writes the same map as a sparse barycentric matrix: `i j w` per non-zero (rows: source vertices, columns:
/// target vertices, 0-based).
/// \param F_target #F by 3 faces of the target mesh
void write_barycentric_matrix(const std::string& path, const std::vector<SurfacePoint>& images,
                              const Eigen::MatrixXi& F_target);

/// The report of a map as JSON: sizes, landmarks, options, timings, energies, distortion, verification.
/// \param a, b the input meshes, read from path_a, path_b
nlohmann::json map_report(const MapResult& map, const std::string& path_a, const TriangleMesh& a,
                          const std::string& path_b, const TriangleMesh& b, const Landmarks& landmarks,
                          const MapOptions& options);

}  // namespace liftmap
