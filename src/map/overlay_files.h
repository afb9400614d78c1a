#pragma once
/// Overlay files (README, "Output folder"): `overlay.obj` and its two tables.
///
/// - `overlay.obj`: the overlay as a mesh on A: `v` = position on A, `f` = triangles (1-based, counter-clockwise).
/// - `overlay_points.txt`: `#` lines naming A and B (map_header.h), then per `v` line of the OBJ,
///   `faceA a0 a1 a2 faceB b0 b1 b2`: the vertex as a point of input A (0-based face, barycentric coordinates in the
///   order of that face's vertices) and as a point of B.
/// - `overlay_faces.txt`: per `f` line, `faceA faceB`: the input faces of A and of B containing the triangle.
/// The two tables are named after the OBJ: `<stem>_points.txt` and `<stem>_faces.txt` in the same folder.

#include <Eigen/Core>
#include <array>
#include <string>

#include "core/overlay.h"
#include "io/map_header.h"

namespace liftmap {

/// The two tables' paths of an overlay OBJ: {<stem>_points.txt, <stem>_faces.txt}.
std::array<std::string, 2> overlay_table_paths(const std::string& obj_path);

/// Writes the overlay OBJ and its two tables (full double precision); the points table's header names the meshes
/// (write_map_header_lines: A the source, B the target) if given.
/// \throw IoError if a file cannot be written
void write_overlay(const std::string& obj_path, const Overlay& overlay, const MapMeshes& meshes = {});

/// Reads an overlay written by write_overlay, checks it against the input meshes and fills in VB (from the
/// points on B).
/// \param VA, FA, VB, FB the input meshes the map was made of (faces in the corner order of their files)
/// \param mesh_paths the files of A and B, for messages
/// \throw IoError (exit 3) naming the file and line for a missing or malformed file, or tables whose row count
///        differs from the OBJ's; InvalidInputError (exit 4) naming the file and line for a face index that is
///        not one of the input mesh's or barycentric coordinates that are not a point of their face, and naming
///        both files if the points table names other meshes than A and B (require_map_mesh).
Overlay read_overlay(const std::string& obj_path, const Eigen::MatrixXd& VA, const Eigen::MatrixXi& FA,
                     const Eigen::MatrixXd& VB, const Eigen::MatrixXi& FB,
                     const std::array<std::string, 2>& mesh_paths = {"A", "B"});

/// The contents of an overlay's three files.
struct OverlayTexts {
  std::string obj;     ///< overlay.obj
  std::string points;  ///< overlay_points.txt
  std::string faces;   ///< overlay_faces.txt
};

/// read_overlay of files already read (tests, fuzzing): the same checks and messages, which name `obj_path` and
/// the tables' paths overlay_table_paths(obj_path).
Overlay read_overlay_texts(const OverlayTexts& texts, const std::string& obj_path, const Eigen::MatrixXd& VA,
                           const Eigen::MatrixXi& FA, const Eigen::MatrixXd& VB, const Eigen::MatrixXi& FB,
                           const std::array<std::string, 2>& mesh_paths = {"A", "B"});

}  // namespace liftmap
