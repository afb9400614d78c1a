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
/// STL's per-triangle corners are merged into one vertex where their coordinates are equal, numbered in order of
/// first appearance. Polygons with more than three vertices are rejected (liftmap does not triangulate behind the
/// user's back). A UTF-8 byte-order mark before a text format's content is skipped. Non-finite coordinates are
/// read as such (check_mesh names them), except in ASCII PLY, which CGAL's reader cannot read them from.
/// \throw IoError naming the file, and the line or element where the format is violated: unreadable file,
///        unknown extension, truncated data, counts that do not match the content, indices out of range,
///        non-numeric coordinates, non-triangle faces; InvalidInputError naming the file and line for a
///        non-finite coordinate in ASCII PLY.
TriangleMesh read_mesh(const std::string& path);

/// read_mesh on a file's content held in memory.
/// \param data the file's bytes
/// \param path the file name: its extension chooses the format, and messages name it
/// \throw as read_mesh
TriangleMesh read_mesh_data(const std::string& data, const std::string& path);

}  // namespace liftmap
