#pragma once
/// Reading triangle meshes: OFF, OBJ, PLY (ASCII and binary), STL (ASCII and binary).

#include <Eigen/Core>
#include <string>

namespace liftmap {

/// A triangle mesh as read from a file: positions and faces, nothing checked beyond the format.
struct TriangleMesh {
  Eigen::MatrixXd V;  ///< #V by 3 vertex positions
  Eigen::MatrixXi F;  ///< #F by 3 vertex indices, 0-based, counter-clockwise seen from outside
};

/// Reads a triangle mesh; the format is chosen by the extension (.off, .obj, .ply, .stl, case-insensitive).
/// STL's per-triangle vertices are merged where their coordinates are identical. Polygons with more than three
/// vertices are rejected (liftmap does not triangulate behind the user's back).
/// \throw IoError naming the file, and the line or element where the format is violated: unreadable file,
///        unknown extension, truncated data, wrong counts, indices out of range, non-numeric or non-finite
///        coordinates, non-triangle faces.
TriangleMesh read_mesh(const std::string& path);

}  // namespace liftmap
