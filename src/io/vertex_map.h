#pragma once
/// Map files: per source vertex, its image as a point of a face of the target mesh (README, "Command line").

#include <iosfwd>
#include <string>
#include <vector>

#include "core/surface_point.h"
#include "io/map_header.h"

namespace liftmap {

/// A map file as read: its images and the meshes its header names.
struct MapFile {
  std::vector<SurfacePoint> images;
  MapMeshes meshes;
};

/// Writes a vertex map: `#` header lines (`header`, then write_map_header_lines of `meshes`), then per source
/// vertex `face b0 b1 b2` (face of the target mesh, barycentric coordinates in the order of that face's vertices,
/// full double precision).
/// \param images per source vertex, a face point of the target
/// \throw IoError if the file cannot be written
void write_vertex_map(const std::string& path, const std::vector<SurfacePoint>& images, const std::string& header,
                      const MapMeshes& meshes = {});

/// How far a map file's barycentric coordinates may be from a point of its face: each at least -kTolerance, their
/// sum within kTolerance of 1 (room for coordinates written with 7 significant digits).
struct BarycentricTolerance {
  static constexpr double kTolerance = 1e-6;
};

/// Reads a vertex map written by write_vertex_map and checks that every line is a point of the target mesh
/// (the meshes its header names are not checked: read_map_file checks them).
/// \param n_target_faces number of faces of the target mesh, to check indices
/// \throw IoError (exit 3) naming the file and line for a malformed line (not 4 numbers) or a face that is not an
///        index of the target mesh; InvalidInputError (exit 4) naming the file and line for barycentric
///        coordinates that are not finite, negative beyond BarycentricTolerance or do not sum to 1 within it
std::vector<SurfacePoint> read_vertex_map(const std::string& path, int n_target_faces);

/// read_vertex_map from a stream; `name` stands for the file in messages.
std::vector<SurfacePoint> read_vertex_map(std::istream& in, const std::string& name, int n_target_faces);

/// read_vertex_map, which also reads the meshes the header names and checks the target against the mesh the map is
/// applied to, before the first map line and again at the end (a file without those lines, as of other tools, is
/// not checked).
/// \throw as read_vertex_map with n_target_faces = target.fingerprint.faces, as read_map_header_line and as
///        require_map_mesh
MapFile read_map_file(const std::string& path, const MeshOfMap& target);

/// read_map_file from a stream; `name` stands for the file in messages.
MapFile read_map_file(std::istream& in, const std::string& name, const MeshOfMap& target);

}  // namespace liftmap
