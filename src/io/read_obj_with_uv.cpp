#include "io/read_obj_with_uv.h"

#include <array>
#include <filesystem>
#include <string_view>
#include <vector>

#include "core/errors.h"
#include "io/line_reader.h"

namespace liftmap {

namespace {

/// Index in [0, n) of a 1-based OBJ index `s` (negative: counting back from the last of the n defined so far).
int obj_index(const LineReader& r, std::string_view s, long long n, const char* what) {
  const long long idx = r.to_int(s);
  const long long i = idx > 0 ? idx - 1 : n + idx;
  if (idx == 0 || i < 0 || i >= n) {
    r.fail("face references " + std::string(what) + " " + std::to_string(idx) + ", but " + std::to_string(n) + " " +
           what + "s are defined before it");
  }
  return static_cast<int>(i);
}

/// The `map_Kd` image of material `name` in the MTL file `path` (resolved from its folder); empty if it has none.
std::string texture_of_material(const std::string& path, const std::string& name) {
  const std::string text = read_file(path, "material file");
  LineReader r(path, text);
  std::string current, first;
  while (r.next_line()) {
    const auto& t = r.tokens();
    if (t[0] == "newmtl") {
      if (t.size() < 2) r.fail("'newmtl' without a name");
      current = t[1];
    } else if (t[0] == "map_Kd") {
      if (t.size() < 2) r.fail("'map_Kd' without a file name");
      std::string image = (std::filesystem::path(path).parent_path() / std::string(t.back())).string();
      if (current == name) return image;
      if (first.empty()) first = image;
    }
  }
  return name.empty() ? first : std::string();
}

struct ObjContent {
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<double, 2>> uvs;
  std::vector<std::array<int, 3>> faces, face_uvs;
  std::string mtllib, material;
};

/// One `f a/ta b/tb c/tc` line into `c`.
void read_face(const LineReader& r, ObjContent& c) {
  const auto& t = r.tokens();
  if (t.size() != 4) {
    r.fail("face has " + std::to_string(t.size() - 1) + " vertices; only triangle meshes are supported");
  }
  std::array<int, 3> f{}, ft{};
  for (size_t k = 0; k < 3; ++k) {
    const std::string_view s = t[k + 1];
    const size_t slash = s.find('/');
    f[k] = obj_index(r, s.substr(0, slash), static_cast<long long>(c.points.size()), "vertex");
    const std::string_view rest = slash == std::string_view::npos ? std::string_view() : s.substr(slash + 1);
    const std::string_view vt = rest.substr(0, rest.find('/'));
    if (vt.empty()) r.fail("face corner '" + std::string(s) + "' has no texture coordinate index (v/vt expected)");
    ft[k] = obj_index(r, vt, static_cast<long long>(c.uvs.size()), "texture coordinate");
  }
  c.faces.push_back(f);
  c.face_uvs.push_back(ft);
}

ObjContent read_obj_content(const std::string& path, const std::string& text) {
  LineReader r(path, text);
  ObjContent c;
  while (r.next_line()) {
    const auto& t = r.tokens();
    const std::string_view key = t[0];
    if (key == "v") {
      if (t.size() < 4) r.fail("vertex needs 3 coordinates");
      c.points.push_back({r.to_double(t[1]), r.to_double(t[2]), r.to_double(t[3])});
    } else if (key == "vt") {
      if (t.size() < 3) r.fail("texture coordinate needs 2 numbers (vt u v)");
      c.uvs.push_back({r.to_double(t[1]), r.to_double(t[2])});
    } else if (key == "f") {
      if (c.uvs.empty()) r.fail("face before any texture coordinate: the OBJ has no 'vt' lines before its faces");
      read_face(r, c);
    } else if (key == "mtllib") {
      if (t.size() < 2) r.fail("'mtllib' without a file name");
      c.mtllib = t.back();
    } else if (key == "usemtl") {
      if (t.size() >= 2 && c.material.empty()) c.material = t[1];
    } else if (key != "vn" && key != "vp" && key != "o" && key != "g" && key != "s" && key != "l" && key != "p") {
      r.fail("unknown OBJ statement '" + std::string(key) + "'");
    }
  }
  if (c.faces.empty()) throw IoError(path + ": no faces");
  return c;
}

}  // namespace

TexturedMesh read_obj_with_uv(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw IoError(path + ": no such file");
  return read_obj_with_uv_text(read_file(path, "mesh file"), path);
}

TexturedMesh read_obj_with_uv_text(const std::string& text, const std::string& path) {
  std::error_code ec;
  const ObjContent c = read_obj_content(path, text);
  TexturedMesh m;
  m.V.resize(static_cast<Eigen::Index>(c.points.size()), 3);
  for (size_t i = 0; i < c.points.size(); ++i)
    for (int k = 0; k < 3; ++k) m.V(static_cast<Eigen::Index>(i), k) = c.points[i][static_cast<size_t>(k)];
  m.UV.resize(static_cast<Eigen::Index>(c.uvs.size()), 2);
  for (size_t i = 0; i < c.uvs.size(); ++i)
    for (int k = 0; k < 2; ++k) m.UV(static_cast<Eigen::Index>(i), k) = c.uvs[i][static_cast<size_t>(k)];
  m.F.resize(static_cast<Eigen::Index>(c.faces.size()), 3);
  m.FT.resize(m.F.rows(), 3);
  for (size_t i = 0; i < c.faces.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      m.F(static_cast<Eigen::Index>(i), k) = c.faces[i][static_cast<size_t>(k)];
      m.FT(static_cast<Eigen::Index>(i), k) = c.face_uvs[i][static_cast<size_t>(k)];
    }
  }
  if (!c.mtllib.empty()) {
    m.material_file = (std::filesystem::path(path).parent_path() / c.mtllib).string();
    if (std::filesystem::exists(m.material_file, ec)) m.texture_path = texture_of_material(m.material_file, c.material);
  }
  return m;
}

}  // namespace liftmap
