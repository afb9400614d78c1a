#include "io/map_header.h"

#include <cctype>
#include <cstring>

#include "core/errors.h"

namespace liftmap {

namespace {

constexpr const char* kSourceLine = "# source mesh: ";
constexpr const char* kTargetLine = "# target mesh: ";

/// The fingerprint after the `prefix` characters of `text` into `slot`, which must be empty.
void read_fingerprint(const std::string& text, size_t prefix, std::optional<MeshFingerprint>& slot,
                      const std::string& where) {
  std::string rest = text.substr(prefix);
  while (!rest.empty() && std::isspace(static_cast<unsigned char>(rest.back()))) rest.pop_back();
  if (slot) throw IoError(where + "a second '" + text.substr(0, prefix - 2) + "' line");
  slot = parse_mesh_fingerprint(rest);
  if (!slot) {
    throw IoError(where + "'" + rest + "' is not a mesh fingerprint ('V vertices, F faces, connectivity fnv1a64:X')");
  }
}

/// Throws if `recorded` (a map file's header) names another mesh than `given`.
void require_mesh(const std::optional<MeshFingerprint>& recorded, const MeshOfMap& given, const char* role,
                  const std::string& map_path) {
  if (!recorded || *recorded == given.fingerprint) return;
  const bool same_counts =
      given.fingerprint.vertices == recorded->vertices && given.fingerprint.faces == recorded->faces;
  throw InvalidInputError(map_path + ": made for a " + role + " mesh with " + to_string(*recorded) + ", but " +
                          given.path + " has " + to_string(given.fingerprint) +
                          (same_counts ? " (the same counts, other faces: a re-meshed or re-ordered mesh)" : "") +
                          ": the map does not belong to this mesh");
}

}  // namespace

void write_map_header_lines(std::FILE* file, const MapMeshes& meshes) {
  if (meshes.source) std::fprintf(file, "%s%s\n", kSourceLine, to_string(*meshes.source).c_str());
  if (meshes.target) std::fprintf(file, "%s%s\n", kTargetLine, to_string(*meshes.target).c_str());
}

bool read_map_header_line(const std::string& text, MapMeshes& meshes, const std::string& where) {
  if (text.rfind(kSourceLine, 0) == 0) {
    read_fingerprint(text, std::strlen(kSourceLine), meshes.source, where);
    return true;
  }
  if (text.rfind(kTargetLine, 0) == 0) {
    read_fingerprint(text, std::strlen(kTargetLine), meshes.target, where);
    return true;
  }
  return false;
}

void require_map_meshes(const MapMeshes& recorded, const MapFileMeshes& given, const std::string& map_path) {
  require_mesh(recorded.target, given.target, "target", map_path);
  if (given.source) require_mesh(recorded.source, *given.source, "source", map_path);
}

}  // namespace liftmap
