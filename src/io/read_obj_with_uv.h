#pragma once
/// Reading an OBJ with texture coordinates and the texture image its material names (`liftmap transfer texture`).

#include <Eigen/Core>
#include <string>

namespace liftmap {

/// A triangle mesh with a UV layout (per-corner texture coordinates) and the image its material names.
struct TexturedMesh {
  Eigen::MatrixXd V;          ///< #V by 3 vertex positions, numbered as read_mesh numbers them
  Eigen::MatrixXi F;          ///< #F by 3 vertex indices, 0-based
  Eigen::MatrixXd UV;         ///< #UV by 2 texture coordinates (u right, v up; the image spans [0,1]^2)
  Eigen::MatrixXi FT;         ///< #F by 3 indices into UV, 0-based, one per corner of F
  std::string material_file;  ///< the `mtllib` file, resolved from the OBJ's folder; empty if none
  std::string texture_path;   ///< the `map_Kd` image of the material used, resolved from the MTL's folder; empty if
                              ///< there is no material file, no such file, or no `map_Kd` in it
};

/// Reads an OBJ whose faces all carry texture coordinates: `v`, `vt u v [w]`, `f v/vt v/vt v/vt` (or `v/vt/vn`;
/// 1-based, negative indices count back), `mtllib`, `usemtl`. The texture image is the `map_Kd` of the first
/// material used (its last token, so `map_Kd` options such as `-s 1 1 1` are skipped; file names with spaces are
/// not supported); a missing material file leaves texture_path empty.
/// \throw IoError naming the file and line: unreadable file, a malformed `v`, `vt` or `f`, a face that is not a
///        triangle, a vertex or texture index out of range, a face without texture coordinates, no `vt` at all;
///        a malformed material file (its line).
TexturedMesh read_obj_with_uv(const std::string& path);

/// read_obj_with_uv of an OBJ's content `text`; `path` names it in messages and is the folder `mtllib` is resolved
/// from. \throw IoError as read_obj_with_uv
TexturedMesh read_obj_with_uv_text(const std::string& text, const std::string& path);

}  // namespace liftmap
