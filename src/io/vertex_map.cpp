#include "io/vertex_map.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/errors.h"
#include "io/input_file.h"
#include "io/line_reader.h"
#include "io/output_file.h"
#include "io/text_line.h"

namespace liftmap {

void write_vertex_map(const std::string& path, const std::vector<SurfacePoint>& images, const std::string& header,
                      const MapMeshes& meshes) {
  OutputFile f(path);
  std::istringstream lines(header);
  for (std::string line; std::getline(lines, line);) std::fprintf(f.get(), "# %s\n", line.c_str());
  write_map_header_lines(f.get(), meshes);
  std::fprintf(f.get(), "# one line per source vertex: face b0 b1 b2 (0-based face of the target mesh)\n");
  TextLine line;
  for (const SurfacePoint& p : images) {
    line.add(p.face.idx).add(p.bary[0]).add(p.bary[1]).add(p.bary[2]).write_to(f.get());
  }
  f.close();
}

namespace {

/// The lines of a map file; the target its header names checked against `target` (if not null) before the first
/// map line and again at the end.
MapFile read_lines(std::istream& in, const std::string& path, int n_target_faces, const MeshOfMap* target) {
  constexpr double kTol = BarycentricTolerance::kTolerance;
  MapFile map;
  std::vector<SurfacePoint>& images = map.images;
  std::string text;
  for (int line_no = 1; std::getline(in, text); ++line_no) {
    const std::string where = path + ":" + std::to_string(line_no) + ": ";
    if (line_no == 1) skip_byte_order_mark(text);
    if (read_map_header_line(text, map.meshes, where)) continue;
    if (const size_t hash = text.find('#'); hash != std::string::npos) text.resize(hash);
    std::istringstream line(text);
    std::vector<std::string> t;
    for (std::string token; line >> token;) t.push_back(token);
    if (t.empty()) continue;
    if (target && images.empty()) require_map_mesh(map.meshes, MapSide::kTarget, *target, path);
    if (t.size() != 4) {
      throw IoError(where + "expected 'face b0 b1 b2', found " + std::to_string(t.size()) + " fields");
    }
    long long face = -1;
    const auto [end, ec] = std::from_chars(t[0].data(), t[0].data() + t[0].size(), face);
    if (ec != std::errc() || end != t[0].data() + t[0].size() || face < 0 || face >= n_target_faces) {
      throw IoError(where + "face " + t[0] + " is not a face index of the target mesh (" +
                    std::to_string(n_target_faces) + " faces)");
    }
    std::array<double, 3> b{};
    for (size_t k = 0; k < 3; ++k) {
      const std::string& s = t[k + 1];
      const char* first = s.data() + (s.size() > 1 && s[0] == '+' ? 1 : 0);
      const auto [p, e] = std::from_chars(first, s.data() + s.size(), b[k]);
      if ((e != std::errc() && e != std::errc::result_out_of_range) || p != s.data() + s.size()) {
        throw IoError(where + "'" + s + "' is not a number");
      }
      // Beyond the range of a double: strtod's +-inf (reported below) or subnormal.
      if (e == std::errc::result_out_of_range) b[k] = std::strtod(s.c_str(), nullptr);
      if (!std::isfinite(b[k])) {
        throw InvalidInputError(where + "barycentric coordinate " + s + " is not finite");
      }
      if (b[k] < -kTol) {
        throw InvalidInputError(where + "barycentric coordinate " + s + " is negative: the point is outside face " +
                                t[0]);
      }
    }
    const double sum = b[0] + b[1] + b[2];
    if (!(std::abs(sum - 1) <= kTol)) {
      throw InvalidInputError(where + "barycentric coordinates sum to " + figure(sum, 10) + ", not 1 (tolerance " +
                              figure(kTol) + ")");
    }
    images.push_back(SurfacePoint::in_face(FaceId(static_cast<int>(face)), b));
  }
  if (in.bad()) throw IoError(path + ": read error");
  if (images.empty()) throw IoError(path + ": no map lines ('face b0 b1 b2')");
  if (target) require_map_mesh(map.meshes, MapSide::kTarget, *target, path);  // lines after the first map line
  return map;
}

}  // namespace

std::vector<SurfacePoint> read_vertex_map(const std::string& path, int n_target_faces) {
  std::ifstream in = open_input_file(path, "map file");
  return read_vertex_map(in, path, n_target_faces);
}

std::vector<SurfacePoint> read_vertex_map(std::istream& in, const std::string& name, int n_target_faces) {
  return read_lines(in, name, n_target_faces, nullptr).images;
}

MapFile read_map_file(const std::string& path, const MeshOfMap& target) {
  std::ifstream in = open_input_file(path, "map file");
  return read_map_file(in, path, target);
}

MapFile read_map_file(std::istream& in, const std::string& name, const MeshOfMap& target) {
  return read_lines(in, name, static_cast<int>(target.fingerprint.faces), &target);
}

}  // namespace liftmap
