#pragma once
/// The lines of a map file's header (and of an overlay's table) that name the meshes the map was made for, so
/// that it is not applied to other meshes: `# source mesh: ` and `# target mesh: ` followed by a MeshFingerprint.

#include <cstdio>
#include <optional>
#include <string>

#include "io/mesh_fingerprint.h"

namespace liftmap {

/// The meshes a map file was made for, as its header records them (either may be absent: files of other tools,
/// or written before the header had them).
struct MapMeshes {
  std::optional<MeshFingerprint> source;  ///< `# source mesh: ...`: the mesh whose vertices the lines are
  std::optional<MeshFingerprint> target;  ///< `# target mesh: ...`: the mesh the lines are points of
};

/// A mesh a map file is applied to: its file and its fingerprint (faces in the corner order of its file).
struct MeshOfMap {
  std::string path;
  MeshFingerprint fingerprint;
};

/// The meshes a map file is applied to: its target, and its source where a command has it.
struct MapFileMeshes {
  MeshOfMap target;
  std::optional<MeshOfMap> source;
};

/// Writes `# source mesh: <fingerprint>` and `# target mesh: <fingerprint>` for the meshes given.
void write_map_header_lines(std::FILE* file, const MapMeshes& meshes);

/// Reads a `# source mesh:` or `# target mesh:` line of a map file into `meshes`.
/// \param text a line of the file, \param where "file:line: " for messages
/// \return false (and nothing read) if the line is not one of them
/// \throw IoError naming `where` if it is one of them but not followed by a fingerprint, or names a mesh twice
bool read_map_header_line(const std::string& text, MapMeshes& meshes, const std::string& where);

/// Checks that the meshes a map file is applied to are those its header names (meshes it does not name, as in
/// files of other tools, are not checked).
/// \throw InvalidInputError (exit 4) naming both files and both fingerprints if the header names another mesh
void require_map_meshes(const MapMeshes& recorded, const MapFileMeshes& given, const std::string& map_path);

}  // namespace liftmap
