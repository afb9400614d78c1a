#include "io/map_header.h"

#include <algorithm>
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

MapMeshes map_header_of_text(const std::string& text, const std::string& path) {
  MapMeshes meshes;
  for (const char* prefix : {kSourceLine, kTargetLine}) {
    for (size_t at = text.find(prefix); at != std::string::npos; at = text.find(prefix, at + 1)) {
      if (at > 0 && text[at - 1] != '\n') continue;  // not at the start of a line
      const size_t end = text.find('\n', at);
      const auto line_no = std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n') + 1;
      read_map_header_line(text.substr(at, end == std::string::npos ? std::string::npos : end - at), meshes,
                           path + ":" + std::to_string(line_no) + ": ");
    }
  }
  return meshes;
}

void require_map_mesh(const MapMeshes& recorded, MapSide side, const MeshOfMap& mesh, const std::string& map_path) {
  if (side == MapSide::kSource) {
    require_mesh(recorded.source, mesh, "source", map_path);
  } else {
    require_mesh(recorded.target, mesh, "target", map_path);
  }
}

}  // namespace liftmap
