#pragma once
/// Writing triangle meshes: OBJ (optionally with per-corner texture coordinates), OFF and PLY.

#include <Eigen/Core>
#include <string>

namespace liftmap {

/// Writes V (#V by 3) and F (#F by 3) in the format named by the extension (.obj, .off, .ply ASCII).
/// \throw IoError if the file cannot be written or the extension is unknown.
void write_mesh(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

/// Writes an OBJ with texture coordinates: `v` from V (#V by 3), `vt` from UV (#UV by 2), faces `f a/ta b/tb
/// c/tc` with vertex indices from F (#F by 3) and texture indices from FT (#F by 3). `mtl`, if non-empty, is
/// written as `mtllib` with `usemtl material`.
/// \throw IoError if the file cannot be written.
void write_obj_with_uv(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                       const Eigen::MatrixXd& UV, const Eigen::MatrixXi& FT, const std::string& mtl = "");

}  // namespace liftmap
