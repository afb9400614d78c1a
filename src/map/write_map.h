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
#include "io/vertex_map.h"
#include "map/map_meshes.h"

namespace liftmap {

/// Writes the same map as a sparse barycentric matrix: `i j w` per non-zero (rows: source vertices, columns:
/// target vertices, 0-based).
/// \param F_target #F by 3 faces of the target mesh
void write_barycentric_matrix(const std::string& path, const std::vector<SurfacePoint>& images,
                              const Eigen::MatrixXi& F_target);

/// The names of every file `liftmap map` writes into its output folder (README, "Command line"), those of
/// write_cut included, report.json last (the order they are written in).
std::vector<std::string> map_output_names();

/// The report of a map as JSON: sizes, landmarks, options, timings, energies, distortion, verification.
/// \param a, b the input meshes, read from path_a, path_b
nlohmann::json map_report(const MapResult& map, const std::string& path_a, const TriangleMesh& a,
                          const std::string& path_b, const TriangleMesh& b, const Landmarks& landmarks,
                          const MapOptions& options);

}  // namespace liftmap
