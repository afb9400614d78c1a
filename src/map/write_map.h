#pragma once
/// The files `liftmap map` and `liftmap cut` write (README, "Output files").

#include <Eigen/Core>
#include <functional>
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

/// What a map was made from, as the report and the output files name it.
struct MapInputs {
  std::string name_a, name_b;  ///< the input files (CLI) or labels given by the caller
  TriangleMesh a, b;           ///< the meshes as mapped: faces reversed where reversed_a / reversed_b
  Landmarks landmarks;
  bool reversed_a = false, reversed_b = false;  ///< faces reversed by reverse_if_inside_out (--fix-orientation)
};

/// The images of a map in the vertex order of the target's faces as given, before reverse_if_inside_out: the
/// order of the map files (barycentric coordinates 1 and 2 swapped if the target's faces were reversed). The swap
/// is its own inverse: it also takes face points as given (landmarks) to the order of the reversed faces.
std::vector<SurfacePoint> images_in_given_order(std::vector<SurfacePoint> images, bool target_reversed);

/// The landmarks with images_in_given_order applied to each side whose faces were reversed: from the tokens as
/// given to the corner order of the reversed faces, and back (the swap is its own inverse). Warnings are kept.
Landmarks landmarks_across_reversal(Landmarks landmarks, bool reversed_a, bool reversed_b);

/// The report of a map as JSON (report.json), with "faces_reversed" per input.
nlohmann::json map_report(const MapResult& map, const MapInputs& inputs, const MapOptions& options);

/// Writes every file of map_output_names() into `dir` (README, "Output of liftmap map"), report.json last, its
/// content `report`; without `pictures`, every file but render.png and distortion.png. The data files are written
/// at once on the calling thread's OpenMP threads (their bytes do not depend on the threads), then the pictures.
/// Call prepare_output_folder first: it removes a previous run's files.
/// \param progress called once before the pictures, if drawn (empty: silent)
/// \throw IoError if a file cannot be written (once every data file has been tried, the first failure in the
///        order of the list in write_map.cpp); report.json is then not written.
void write_map_folder(const std::string& dir, const MapResult& map, const MapInputs& inputs,
                      const nlohmann::json& report, bool pictures = true,
                      const std::function<void(const std::string&, const std::string&)>& progress = {});

/// The report of a map as JSON: sizes, landmarks, options, timings, energies, distortion, verification.
/// \param a, b the input meshes, read from path_a, path_b
nlohmann::json map_report(const MapResult& map, const std::string& path_a, const TriangleMesh& a,
                          const std::string& path_b, const TriangleMesh& b, const Landmarks& landmarks,
                          const MapOptions& options);

}  // namespace liftmap
