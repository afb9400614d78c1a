#pragma once
/// A mesh's fingerprint: what a map file records of the meshes it was made for, so that it is not applied to others.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>

namespace liftmap {

/// The vertex and face counts of a mesh and a hash of its faces (its connectivity, not its positions: a map file
/// applies to any mesh with the same connectivity, e.g. another pose of the same mesh).
struct MeshFingerprint {
  long long vertices = 0;
  long long faces = 0;
  std::uint64_t connectivity = 0;  ///< 64-bit FNV-1a of the face indices in file order, row by row

  bool operator==(const MeshFingerprint&) const = default;
};

/// The fingerprint of a mesh with `n_vertices` vertices and faces F (#F by 3, in the corner order of its file).
MeshFingerprint mesh_fingerprint(Eigen::Index n_vertices, const Eigen::MatrixXi& F);

/// "3000 vertices, 5996 faces, connectivity fnv1a64:0123456789abcdef": the text of a map file's header line.
std::string to_string(const MeshFingerprint& fingerprint);

/// The fingerprint of a text written by to_string (hexadecimal digits in either case); nullopt if `text` is not one.
std::optional<MeshFingerprint> parse_mesh_fingerprint(const std::string& text);

}  // namespace liftmap
