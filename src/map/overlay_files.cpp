#include "map/overlay_files.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <vector>

#include "core/errors.h"
#include "io/line_reader.h"
#include "io/map_header.h"
#include "io/output_file.h"
#include "io/read_mesh.h"
#include "io/text_line.h"
#include "io/vertex_map.h"
#include "io/write_mesh.h"
#include "map/transfer.h"

namespace liftmap {

namespace {

/// A table cell that must be a face index of a mesh with `n_faces` faces.
int face_index(double x, int n_faces, const std::string& where, const char* mesh) {
  if (!(x >= 0 && x < n_faces && x == std::floor(x))) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", x);
    throw InvalidInputError(where + text + " is not a face index of " + mesh + " (" + std::to_string(n_faces) +
                            " faces)");
  }
  return static_cast<int>(x);
}

/// Columns c..c+3 of row i: a face and barycentric coordinates that make a point of it.
SurfacePoint face_point(const Eigen::MatrixXd& T, Eigen::Index i, Eigen::Index c, int n_faces, const std::string& where,
                        const char* mesh) {
  constexpr double kTol = BarycentricTolerance::kTolerance;
  const int f = face_index(T(i, c), n_faces, where, mesh);
  std::array<double, 3> b{T(i, c + 1), T(i, c + 2), T(i, c + 3)};
  for (double x : b) {
    if (!std::isfinite(x) || x < -kTol) {
      char text[32];
      std::snprintf(text, sizeof text, "%.17g", x);
      throw InvalidInputError(where + "barycentric coordinate " + text + " on " + mesh + " is not a point of its face");
    }
  }
  if (std::abs(b[0] + b[1] + b[2] - 1.0) > kTol) {
    throw InvalidInputError(where + "barycentric coordinates on " + mesh + " do not sum to 1");
  }
  return SurfacePoint::in_face(FaceId(f), clamp_barycentric(b));
}

}  // namespace

std::array<std::string, 2> overlay_table_paths(const std::string& obj_path) {
  const std::filesystem::path p(obj_path);
  const std::string stem = (p.parent_path() / p.stem()).string();
  return {stem + "_points.txt", stem + "_faces.txt"};
}

void write_overlay(const std::string& obj_path, const Overlay& overlay, const MapMeshes& meshes) {
  const auto [points_path, faces_path] = overlay_table_paths(obj_path);
  write_mesh(obj_path, overlay.VA, overlay.F);
  {
    OutputFile f(points_path);
    std::fprintf(f.get(),
                 "# liftmap overlay: per vertex of %s, its point on A and on B\n"
                 "# faceA a0 a1 a2 faceB b0 b1 b2 (0-based faces of the input meshes, barycentric coordinates)\n",
                 std::filesystem::path(obj_path).filename().string().c_str());
    write_map_header_lines(f.get(), meshes);
    TextLine line;
    for (size_t i = 0; i < overlay.on_a.size(); ++i) {
      const SurfacePoint& a = overlay.on_a[i];
      const SurfacePoint& b = overlay.on_b[i];
      line.add(a.face.idx).add(a.bary[0]).add(a.bary[1]).add(a.bary[2]);
      line.add(b.face.idx).add(b.bary[0]).add(b.bary[1]).add(b.bary[2]).write_to(f.get());
    }
    f.close();
  }
  OutputFile f(faces_path);
  std::fprintf(f.get(), "# liftmap overlay: per triangle of %s, the input faces of A and of B containing it\n",
               std::filesystem::path(obj_path).filename().string().c_str());
  TextLine line;
  for (Eigen::Index t = 0; t < overlay.F.rows(); ++t)
    line.add(overlay.face_a(t)).add(overlay.face_b(t)).write_to(f.get());
  f.close();
}

Overlay read_overlay(const std::string& obj_path, const Eigen::MatrixXd& VA, const Eigen::MatrixXi& FA,
                     const Eigen::MatrixXd& VB, const Eigen::MatrixXi& FB,
                     const std::array<std::string, 2>& mesh_paths) {
  const auto [points_path, faces_path] = overlay_table_paths(obj_path);
  std::error_code ec;
  if (!std::filesystem::exists(obj_path, ec)) throw IoError(obj_path + ": no such file");
  OverlayTexts texts;
  texts.obj = read_file(obj_path, "overlay file");
  texts.points = read_file(points_path, "overlay table");
  texts.faces = read_file(faces_path, "overlay table");
  return read_overlay_texts(texts, obj_path, VA, FA, VB, FB, mesh_paths);
}

Overlay read_overlay_texts(const OverlayTexts& texts, const std::string& obj_path, const Eigen::MatrixXd& VA,
                           const Eigen::MatrixXi& FA, const Eigen::MatrixXd& VB, const Eigen::MatrixXi& FB,
                           const std::array<std::string, 2>& mesh_paths) {
  const auto [points_path, faces_path] = overlay_table_paths(obj_path);
  const MapMeshes named = map_header_of_text(texts.points, points_path);
  require_map_mesh(named, MapSide::kSource, {mesh_paths[0], mesh_fingerprint(VA.rows(), FA)}, points_path);
  require_map_mesh(named, MapSide::kTarget, {mesh_paths[1], mesh_fingerprint(VB.rows(), FB)}, points_path);
  const TriangleMesh mesh = read_mesh_data(texts.obj, obj_path);
  std::vector<int> point_lines, face_lines;
  std::istringstream points(texts.points), faces(texts.faces);
  const Eigen::MatrixXd P = read_attributes(points, points_path, &point_lines);
  const Eigen::MatrixXd T = read_attributes(faces, faces_path, &face_lines);
  if (P.cols() != 8 || P.rows() != mesh.V.rows()) {
    throw IoError(points_path + ": expected " + std::to_string(mesh.V.rows()) +
                  " rows of 8 numbers (one per vertex of " + obj_path + "), found " + std::to_string(P.rows()) +
                  " rows of " + std::to_string(P.cols()));
  }
  if (T.cols() != 2 || T.rows() != mesh.F.rows()) {
    throw IoError(faces_path + ": expected " + std::to_string(mesh.F.rows()) + " rows of 2 numbers (one per face of " +
                  obj_path + "), found " + std::to_string(T.rows()) + " rows of " + std::to_string(T.cols()));
  }
  Overlay o;
  o.VA = mesh.V;
  o.F = mesh.F;
  o.on_a.resize(static_cast<size_t>(P.rows()));
  o.on_b.resize(static_cast<size_t>(P.rows()));
  const auto nfa = static_cast<int>(FA.rows()), nfb = static_cast<int>(FB.rows());
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const std::string where = points_path + ":" + std::to_string(point_lines[static_cast<size_t>(i)]) + ": ";
    o.on_a[static_cast<size_t>(i)] = face_point(P, i, 0, nfa, where, "A");
    o.on_b[static_cast<size_t>(i)] = face_point(P, i, 4, nfb, where, "B");
  }
  o.VB = interpolate_at(FB, VB, o.on_b);
  o.face_a.resize(T.rows());
  o.face_b.resize(T.rows());
  for (Eigen::Index t = 0; t < T.rows(); ++t) {
    const std::string where = faces_path + ":" + std::to_string(face_lines[static_cast<size_t>(t)]) + ": ";
    o.face_a(t) = face_index(T(t, 0), nfa, where, "A");
    o.face_b(t) = face_index(T(t, 1), nfb, where, "B");
  }
  (void)VA;
  return o;
}

}  // namespace liftmap
