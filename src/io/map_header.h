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

/// Writes `# source mesh: <fingerprint>` and `# target mesh: <fingerprint>` for the meshes given.
void write_map_header_lines(std::FILE* file, const MapMeshes& meshes);

/// Reads a `# source mesh:` or `# target mesh:` line of a map file into `meshes`.
/// \param text a line of the file, \param where "file:line: " for messages
/// \return false (and nothing read) if the line is not one of them
/// \throw IoError naming `where` if it is one of them but not followed by a fingerprint, or names a mesh twice
bool read_map_header_line(const std::string& text, MapMeshes& meshes, const std::string& where);

/// The meshes named by the `# source mesh:` and `# target mesh:` lines anywhere in a text (read_map_header_line).
/// \param path the file, for messages
MapMeshes map_header_of_text(const std::string& text, const std::string& path);

/// Which mesh of a map file: the one whose vertices its lines are, or the one its lines are points of.
enum class MapSide { kSource, kTarget };

/// Checks that a mesh a map file is applied to is the one its header names on that side (if it names one: files of
/// other tools do not). Commands that use a map per source vertex need of the source only its vertex count, which
/// they compare with the map's line count; the overlay's faces lie in faces of both meshes.
/// \throw InvalidInputError (exit 4) naming both files and both fingerprints if the header names another mesh
void require_map_mesh(const MapMeshes& recorded, MapSide side, const MeshOfMap& mesh, const std::string& map_path);

}  // namespace liftmap
