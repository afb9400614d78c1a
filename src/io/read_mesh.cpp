#include "io/read_mesh.h"

#include <CGAL/IO/PLY.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "io/line_reader.h"

// OFF, OBJ and STL are parsed here because their errors must name the line or the count; CGAL's readers only
// say "failed". PLY (many property layouts, three encodings) goes through CGAL's reader.

namespace liftmap {

namespace {

using Point = std::array<double, 3>;
using Triangle = std::array<int, 3>;

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

TriangleMesh to_matrices(const std::vector<Point>& points, const std::vector<Triangle>& triangles) {
  TriangleMesh m;
  m.V.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (size_t i = 0; i < points.size(); ++i) {
    for (int k = 0; k < 3; ++k) m.V(static_cast<Eigen::Index>(i), k) = points[i][static_cast<size_t>(k)];
  }
  m.F.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (size_t i = 0; i < triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) m.F(static_cast<Eigen::Index>(i), k) = triangles[i][static_cast<size_t>(k)];
  }
  return m;
}

TriangleMesh read_off(const std::string& path, const std::string& text) {
  LineReader r(path, text);
  if (!r.next_line()) throw IoError(path + ": empty file");
  std::vector<std::string_view> header = r.tokens();
  const std::string_view magic = header[0];
  if (magic.size() < 3 || magic.substr(magic.size() - 3) != "OFF") r.fail("expected an 'OFF' header");
  if (magic != "OFF" && magic != "COFF" && magic != "NOFF" && magic != "CNOFF") {
    r.fail("'" + std::string(magic) + "' variant of OFF is not supported (use plain or colour OFF)");
  }
  if (header.size() > 1 && header[1] == "BINARY") r.fail("binary OFF is not supported");
  header.erase(header.begin());
  if (header.empty()) {
    if (!r.next_line()) r.fail("missing the line with vertex and face counts");
    header = r.tokens();
  }
  if (header.size() < 2) r.fail("expected 'vertices faces [edges]' counts");
  if (header.size() > 3) {
    r.fail(std::to_string(header.size() - 3) + " more values after the 'vertices faces edges' counts: liftmap reads " +
           "an OFF with one vertex or face per line (is the file written on one line?)");
  }
  const long long nv = r.to_int(header[0]);
  const long long nf = r.to_int(header[1]);
  if (nv < 0 || nf < 0) r.fail("negative vertex or face count");
  // Never trust the counts for allocation: each vertex needs at least 6 bytes of text.
  const auto max_items = static_cast<long long>(text.size() / 6 + 1);
  if (nv > max_items || nf > max_items) {
    r.fail("truncated or wrong counts: the header announces " + std::to_string(nv) + " vertices and " +
           std::to_string(nf) + " faces, more than a file of " + std::to_string(text.size()) + " bytes can hold");
  }
  std::vector<Point> points;
  points.reserve(static_cast<size_t>(nv));
  for (long long i = 0; i < nv; ++i) {
    if (!r.next_line()) {
      throw IoError(path + ": truncated: the header announces " + std::to_string(nv) + " vertices, found " +
                    std::to_string(i));
    }
    const auto& t = r.tokens();
    if (t.size() < 3) r.fail("vertex " + std::to_string(i) + " needs 3 coordinates");
    points.push_back({r.to_double(t[0]), r.to_double(t[1]), r.to_double(t[2])});
  }
  std::vector<Triangle> triangles;
  triangles.reserve(static_cast<size_t>(nf));
  for (long long i = 0; i < nf; ++i) {
    if (!r.next_line()) {
      throw IoError(path + ": truncated: the header announces " + std::to_string(nf) + " faces, found " +
                    std::to_string(i));
    }
    const auto& t = r.tokens();
    const long long n = r.to_int(t[0]);
    if (n != 3) {
      r.fail("face " + std::to_string(i) + " has " + std::to_string(n) +
             " vertices; only triangle meshes are supported");
    }
    if (t.size() < 4) r.fail("face " + std::to_string(i) + " lists fewer than 3 vertex indices");
    Triangle tri{};
    for (int k = 0; k < 3; ++k) {
      const long long v = r.to_int(t[static_cast<size_t>(k + 1)]);
      if (v < 0 || v >= nv) {
        r.fail("face " + std::to_string(i) + " references vertex " + std::to_string(v) + ", but there are " +
               std::to_string(nv) + " vertices");
      }
      tri[static_cast<size_t>(k)] = static_cast<int>(v);
    }
    triangles.push_back(tri);
  }
  if (r.next_line()) {
    r.fail("the header announces " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
           " faces, but the file goes on: the counts do not match the content");
  }
  return to_matrices(points, triangles);
}

TriangleMesh read_obj(const std::string& path, const std::string& text) {
  LineReader r(path, text);
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  while (r.next_line()) {
    const auto& t = r.tokens();
    const std::string_view key = t[0];
    if (key == "v") {
      if (t.size() < 4) r.fail("vertex needs 3 coordinates");
      points.push_back({r.to_double(t[1]), r.to_double(t[2]), r.to_double(t[3])});
    } else if (key == "f") {
      if (t.size() != 4) {
        r.fail("face has " + std::to_string(t.size() - 1) + " vertices; only triangle meshes are supported");
      }
      Triangle tri{};
      for (int k = 0; k < 3; ++k) {
        std::string_view s = t[static_cast<size_t>(k + 1)];
        s = s.substr(0, s.find('/'));  // "v", "v/vt", "v//vn", "v/vt/vn": the vertex index comes first
        const long long idx = r.to_int(s);
        const auto n = static_cast<long long>(points.size());
        // OBJ indices are 1-based; negative ones count back from the last vertex read so far.
        const long long v = idx > 0 ? idx - 1 : n + idx;
        if (idx == 0 || v < 0 || v >= n) {
          r.fail("face references vertex " + std::to_string(idx) + ", but " + std::to_string(n) +
                 " vertices are defined before it");
        }
        tri[static_cast<size_t>(k)] = static_cast<int>(v);
      }
      triangles.push_back(tri);
    } else if (key == "vt" || key == "vn" || key == "vp" || key == "o" || key == "g" || key == "s" || key == "usemtl" ||
               key == "mtllib" || key == "l" || key == "p") {
      continue;  // attributes and grouping carry no geometry liftmap uses
    } else {
      r.fail("unknown OBJ statement '" + std::string(key) + "'");
    }
  }
  if (points.empty() && triangles.empty()) throw IoError(path + ": empty file (no vertices, no faces)");
  return to_matrices(points, triangles);
}

/// Merges STL's per-triangle corners into vertices in order of first appearance, as CGAL's reader did: the
/// numbering landmark files of STL meshes rely on. Corners merge where their coordinates are equal (0 and -0
/// too).
class CornerMerger {
 public:
  int index(const Point& p) {
    std::array<std::uint64_t, 3> key{};
    for (size_t k = 0; k < 3; ++k) {
      const double x = p[k] == 0 ? 0.0 : p[k];
      std::memcpy(&key[k], &x, sizeof x);
    }
    const auto [it, fresh] = index_.emplace(key, static_cast<int>(points.size()));
    if (fresh) points.push_back(p);
    return it->second;
  }
  std::vector<Point> points;

 private:
  std::map<std::array<std::uint64_t, 3>, int> index_;
};

TriangleMesh read_binary_stl(const std::string& path, const std::string& data) {
  constexpr size_t kHeader = 84, kTriangle = 50;
  if (data.size() < kHeader) {
    throw IoError(path + ": truncated binary STL: " + std::to_string(data.size()) +
                  " bytes, less than its 84-byte header");
  }
  std::uint32_t n = 0;
  std::memcpy(&n, data.data() + 80, 4);
  const size_t expected = kHeader + kTriangle * static_cast<size_t>(n);
  if (data.size() != expected) {
    throw IoError(path + ": the binary STL header announces " + std::to_string(n) + " triangles (" +
                  std::to_string(expected) + " bytes), but the file has " + std::to_string(data.size()) +
                  " bytes (room for " + std::to_string((data.size() - kHeader) / kTriangle) +
                  " triangles): the count does not match the content");
  }
  CornerMerger merger;
  std::vector<Triangle> triangles(n);
  for (size_t t = 0; t < n; ++t) {
    const char* record = data.data() + kHeader + kTriangle * t + 12;  // after the normal
    for (size_t k = 0; k < 3; ++k) {
      float xyz[3];
      std::memcpy(xyz, record + 12 * k, sizeof xyz);
      triangles[t][k] = merger.index({xyz[0], xyz[1], xyz[2]});
    }
  }
  return to_matrices(merger.points, triangles);
}

TriangleMesh read_ascii_stl(const std::string& path, const std::string& text) {
  LineReader r(path, text);
  if (!r.next_line() || r.tokens()[0] != "solid") throw IoError(path + ": expected 'solid' to start an ASCII STL");
  CornerMerger merger;
  std::vector<Triangle> triangles;
  std::vector<int> corners;
  bool in_facet = false, ended = false;
  while (r.next_line()) {
    const auto& t = r.tokens();
    const std::string_view key = t[0];
    if (ended) r.fail("content after 'endsolid'");
    if (key == "facet") {
      if (in_facet) r.fail("'facet' inside a facet (missing 'endfacet')");
      in_facet = true;
      corners.clear();
    } else if (key == "outer" || key == "endloop") {
      if (!in_facet) r.fail("'" + std::string(key) + "' outside a facet");
    } else if (key == "vertex") {
      if (!in_facet) r.fail("'vertex' outside a facet");
      if (t.size() != 4) r.fail("vertex needs 3 coordinates");
      corners.push_back(merger.index({r.to_double(t[1]), r.to_double(t[2]), r.to_double(t[3])}));
    } else if (key == "endfacet") {
      if (!in_facet) r.fail("'endfacet' without 'facet'");
      if (corners.size() != 3) {
        r.fail("facet " + std::to_string(triangles.size()) + " has " + std::to_string(corners.size()) +
               " vertices; only triangle meshes are supported");
      }
      triangles.push_back({corners[0], corners[1], corners[2]});
      in_facet = false;
    } else if (key == "endsolid") {
      if (in_facet) r.fail("'endsolid' inside a facet");
      ended = true;
    } else {
      r.fail("unknown ASCII STL keyword '" + std::string(key) + "'");
    }
  }
  if (in_facet) throw IoError(path + ": truncated: the last facet has no 'endfacet'");
  if (!ended) throw IoError(path + ": truncated: no 'endsolid'");
  return to_matrices(merger.points, triangles);
}

TriangleMesh read_stl(const std::string& path, const std::string& data) {
  // A binary STL's 80-byte header may start with "solid" too: its size, 84 + 50 n, decides.
  if (data.size() >= 84) {
    std::uint32_t n = 0;
    std::memcpy(&n, data.data() + 80, 4);
    if (data.size() == 84 + 50 * static_cast<size_t>(n)) return read_binary_stl(path, data);
  }
  size_t start = data.rfind(kByteOrderMark, 0) == 0 ? kByteOrderMark.size() : 0;
  while (start < data.size() && std::isspace(static_cast<unsigned char>(data[start]))) ++start;
  if (data.compare(start, 5, "solid") == 0 && data.find('\0') == std::string::npos) return read_ascii_stl(path, data);
  return read_binary_stl(path, data);
}

/// The line after the header of an ASCII PLY whose first token is not a finite number, if any: CGAL's
/// reader fails on "nan" and "inf", which are non-finite coordinates to report as such.
std::optional<std::pair<int, std::string>> ply_non_finite_token(const std::string& path, const std::string& text) {
  if (text.find("format ascii") == std::string::npos) return std::nullopt;
  LineReader r(path, text, false);
  bool in_body = false;
  while (r.next_line()) {
    if (!in_body) {
      in_body = r.tokens()[0] == "end_header";
      continue;
    }
    for (const std::string_view token : r.tokens()) {
      double x = 0;
      std::string_view s = token;
      if (!s.empty() && (s.front() == '+' || s.front() == '-')) s.remove_prefix(1);
      const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), x);
      if (ec == std::errc() && p == s.data() + s.size() && !std::isfinite(x)) {
        return std::pair{r.line_no(), std::string(token)};
      }
    }
  }
  return std::nullopt;
}

bool is_ply_type(std::string_view t) {
  for (const char* known : {"char", "uchar", "short", "ushort", "int", "uint", "float", "double", "int8", "uint8",
                            "int16", "uint16", "int32", "uint32", "float32", "float64"}) {
    if (t == known) return true;
  }
  return false;
}

/// Checks the header of a PLY file before CGAL's reader sees it, which does not check what it relies on (both
/// found by fuzzing): a "property" line before any "element" indexes an empty list of elements, and a vertex
/// coordinate of an integer type is read through a null pointer. Its list counts size a buffer before
/// anything is read: only unsigned 8- and 16-bit count types are accepted, so that a count cannot ask for
/// gigabytes or be negative.
void check_ply_header(const std::string& path, const std::string& data) {
  // Line by line as CGAL reads it, up to the first line whose first word is "end_header" (that word elsewhere in
  // a line, or followed by '#', does not end the header: both found by fuzzing).
  LineReader r(path, data, false);
  if (!r.next_line() || r.tokens()[0] != "ply") throw IoError(path + ": not a PLY file: expected 'ply' first");
  bool ended = false;
  bool have_format = false;
  std::string element;  // the element the properties belong to
  int vertex_line = 0;
  std::array<bool, 3> have_xyz{};
  auto check_vertex_element = [&] {
    if (vertex_line == 0) return;
    for (size_t k = 0; k < 3; ++k) {
      if (!have_xyz[k]) {
        throw IoError(path + ":" + std::to_string(vertex_line) + ": the vertex element has no '" +
                      std::string(1, static_cast<char>('x' + k)) + "' property");
      }
    }
    vertex_line = 0;
  };
  while (!ended && r.next_line()) {
    const auto& t = r.tokens();
    if (t[0] == "end_header") {
      ended = true;
    } else if (t[0] == "format") {
      if (t.size() != 3 || (t[1] != "ascii" && t[1] != "binary_little_endian" && t[1] != "binary_big_endian")) {
        r.fail("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      }
      have_format = true;
    } else if (t[0] == "element") {
      if (t.size() != 3) r.fail("expected 'element NAME COUNT'");
      const long long n = r.to_int(t[2]);
      // Every element takes at least one byte: a larger count cannot be the file's.
      if (n < 0 || static_cast<unsigned long long>(n) > data.size()) {
        r.fail("element '" + std::string(t[1]) + "' announces " + std::string(t[2]) + " items, more than a file of " +
               std::to_string(data.size()) + " bytes can hold");
      }
      check_vertex_element();
      element = t[1];
      if (element == "vertex" || element == "vertices") {
        vertex_line = r.line_no();
        have_xyz = {};
      }
    } else if (t[0] == "property") {
      if (element.empty()) r.fail("'property' before any 'element'");
      if (t.size() == 5 && t[1] == "list") {
        // Unsigned: CGAL casts a signed count of -3 to a size_t of 2^64 - 3 and its vector throws (fuzz_ply).
        if (t[2] != "uchar" && t[2] != "uint8" && t[2] != "ushort" && t[2] != "uint16") {
          r.fail("list count type '" + std::string(t[2]) + "' is not supported (uchar or ushort)");
        }
        if (!is_ply_type(t[3])) r.fail("unknown PLY type '" + std::string(t[3]) + "'");
        if (vertex_line != 0 && (t[4] == "x" || t[4] == "y" || t[4] == "z")) {
          r.fail("vertex coordinate '" + std::string(t[4]) + "' is a list; float or double is needed");
        }
      } else if (t.size() == 3) {
        if (!is_ply_type(t[1])) r.fail("unknown PLY type '" + std::string(t[1]) + "'");
        if (vertex_line != 0 && t[2].size() == 1 && t[2][0] >= 'x' && t[2][0] <= 'z') {
          if (t[1] != "float" && t[1] != "double" && t[1] != "float32" && t[1] != "float64") {
            r.fail("vertex coordinate '" + std::string(t[2]) + "' has type '" + std::string(t[1]) +
                   "'; float or double is needed");
          }
          have_xyz[static_cast<size_t>(t[2][0] - 'x')] = true;
        }
      } else {
        r.fail("expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
      }
    } else if (t[0] != "comment" && t[0] != "obj_info") {
      r.fail("unknown PLY header keyword '" + std::string(t[0]) + "'");
    }
  }
  if (!ended) throw IoError(path + ": not a PLY file: no 'end_header' line");
  check_vertex_element();
  if (!have_format) throw IoError(path + ": not a PLY file: no 'format' line");
}

TriangleMesh read_ply(const std::string& path, const std::string& data) {
  // CGAL's reader wants the "ply" signature first: a byte-order mark before it is skipped.
  const std::string body = data.rfind(kByteOrderMark, 0) == 0 ? data.substr(kByteOrderMark.size()) : data;
  check_ply_header(path, body);
  std::istringstream in(body);
  std::vector<CGAL::Simple_cartesian<double>::Point_3> cgal_points;
  std::vector<std::vector<std::size_t>> polygons;
  // CGAL's readers print their own diagnostics to std::cerr; ours below is the one the user should see.
  std::ostringstream cgal_diagnostics;
  std::streambuf* const cerr_buffer = std::cerr.rdbuf(cgal_diagnostics.rdbuf());
  const bool ok = CGAL::IO::read_PLY(in, cgal_points, polygons);
  std::cerr.rdbuf(cerr_buffer);
  if (!ok) {
    if (const auto bad = ply_non_finite_token(path, data)) {
      throw InvalidInputError(path + ":" + std::to_string(bad->first) + ": non-finite coordinate '" + bad->second +
                              "'");
    }
    throw IoError(path + ": not a valid PLY file (truncated, wrong counts or corrupt data)");
  }
  std::vector<Point> points;
  points.reserve(cgal_points.size());
  for (const auto& p : cgal_points) points.push_back({p.x(), p.y(), p.z()});
  std::vector<Triangle> triangles;
  triangles.reserve(polygons.size());
  for (size_t i = 0; i < polygons.size(); ++i) {
    const auto& poly = polygons[i];
    if (poly.size() != 3) {
      throw IoError(path + ": face " + std::to_string(i) + " has " + std::to_string(poly.size()) +
                    " vertices; only triangle meshes are supported");
    }
    Triangle tri{};
    for (size_t k = 0; k < 3; ++k) {
      if (poly[k] >= points.size()) {
        // CGAL stores the file's signed index in a size_t: -5 arrives as 2^64 - 5.
        const auto index = static_cast<std::int64_t>(poly[k]);
        throw IoError(path + ": face " + std::to_string(i) + " references vertex " + std::to_string(index) +
                      ", but there are " + std::to_string(points.size()) + " vertices");
      }
      tri[k] = static_cast<int>(poly[k]);
    }
    triangles.push_back(tri);
  }
  return to_matrices(points, triangles);
}

}  // namespace

TriangleMesh read_mesh_data(const std::string& data, const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext != ".off" && ext != ".obj" && ext != ".ply" && ext != ".stl") {
    throw IoError(path + ": unknown mesh format '" + ext + "' (expected .off, .obj, .ply or .stl)");
  }
  if (data.empty() || data == kByteOrderMark) throw IoError(path + ": empty file");
  TriangleMesh mesh = ext == ".off"   ? read_off(path, data)
                      : ext == ".obj" ? read_obj(path, data)
                      : ext == ".ply" ? read_ply(path, data)
                                      : read_stl(path, data);
  if (mesh.F.rows() == 0) throw IoError(path + ": the file contains no complete face (truncated?)");
  return mesh;
}

TriangleMesh read_mesh(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext != ".off" && ext != ".obj" && ext != ".ply" && ext != ".stl") {
    throw IoError(path + ": unknown mesh format '" + ext + "' (expected .off, .obj, .ply or .stl)");
  }
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw IoError(path + ": no such file");
  return read_mesh_data(read_file(path, "mesh file"), path);
}

}  // namespace liftmap
