#include "io/landmarks.h"

#include <Eigen/Geometry>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <utility>

#include "core/errors.h"
#include "core/nearest_surface_point.h"
#include "io/input_file.h"
#include "io/line_reader.h"
#include "io/output_file.h"

namespace liftmap {

namespace {

/// Barycentric coordinates may leave [0, 1] and their sum may leave 1 by this much (rounding in the writer).
constexpr double kBarycentricTolerance = 1e-9;
/// A 3D point farther than this fraction of the bounding box diagonal from the surface gets a warning.
constexpr double kFarFromSurface = 0.01;
/// A point whose barycentric coordinate is below this (closer to a side of its face than this fraction of the face's
/// height) is moved onto the side: a vertex that near a side leaves a sliver in the refined mesh, whose flattening
/// loses precision (on sphere-ellipsoid, f's max distortion was 1e5 at 1e-6, and the verification failed at 1e-9).
constexpr double kNearSide = 1e-3;
/// Two landmarks of one side closer than this fraction of the bounding box diagonal are at one point.
constexpr double kSamePoint = 1e-12;
/// Two landmarks of one side, one of them inside a face, closer than this fraction of that face's size
/// (sqrt of its area; the smaller face if both are) are too close to cut apart: the cut between them holds
/// triangles too thin to flatten. The sphere mapped onto a copy of itself scaled by 2, with two landmarks in one face,
/// is the identity down to 1.5e-7 of the face's size apart; at 4.7e-8 its verification failed (exit 5), at 4.7e-9 no
/// start could be found.
constexpr double kTooClose = 1e-6;

[[noreturn]] void fail(const std::string& path, int line, const std::string& what) {
  throw InvalidInputError(path + ":" + std::to_string(line) + ": " + what);
}

std::string number(double x) {
  char s[32];
  std::snprintf(s, sizeof s, "%.6g", x);
  return s;
}

/// One mesh as the reader sees it: its vertex count, and its geometry when surface points are accepted.
class LandmarkMesh {
 public:
  LandmarkMesh(char name, int n_vertices) : name(name), n_vertices(n_vertices) {}
  LandmarkMesh(char name, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F)
      : name(name), n_vertices(static_cast<int>(V.rows())), V_(&V), F_(&F) {
    if (V.rows() > 0) diagonal_ = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  }

  [[nodiscard]] bool has_geometry() const { return V_ != nullptr; }
  [[nodiscard]] int n_faces() const { return static_cast<int>(F_->rows()); }
  [[nodiscard]] double diagonal() const { return diagonal_; }
  [[nodiscard]] int corner(int face, int k) const { return (*F_)(face, k); }

  /// The size of the face a landmark lies in, sqrt of its area; infinite for a vertex (its own geometry is the
  /// mesh's, checked by check_mesh).
  [[nodiscard]] double face_size(const SurfacePoint& p) const {
    if (p.kind != SurfacePoint::Kind::kFace) return std::numeric_limits<double>::infinity();
    return liftmap::face_size(*V_, *F_, p.face.idx);
  }

  [[nodiscard]] Eigen::Vector3d position(const SurfacePoint& p) const {
    if (p.kind == SurfacePoint::Kind::kVertex) return V_->row(p.vertex.idx).transpose();
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) x += p.bary[static_cast<size_t>(k)] * V_->row(corner(p.face.idx, k)).transpose();
    return x;
  }

  /// The nearest point of the surface; the search tree is built at the first call.
  [[nodiscard]] NearestSurfacePoint nearest(const Eigen::Vector3d& x) {
    if (!locator_) locator_ = std::make_unique<SurfaceLocator>(*V_, *F_);
    return locator_->nearest(x);
  }

  char name;
  int n_vertices;

 private:
  const Eigen::MatrixXd* V_ = nullptr;
  const Eigen::MatrixXi* F_ = nullptr;
  double diagonal_ = 0;
  std::unique_ptr<SurfaceLocator> locator_;
};

/// A token read but not yet checked against the other landmarks: a vertex index (possibly out of range), or a
/// face point.
struct Token {
  bool is_vertex = true;
  long long vertex = -1;
  SurfacePoint point;
};

/// The face point of barycentric coordinates b in `face`, a vertex point if only one of them is positive; a point
/// nearer to a side than kNearSide moved onto it, with a warning naming the line if that moves it farther than
/// rounding (kSamePoint).
/// `where` names the landmark in the warning: "file:line" or "name: row i".
Token face_token(const std::string& where, const LandmarkMesh& mesh, int face, std::array<double, 3> b,
                 std::vector<std::string>& warnings) {
  b = clamp_barycentric(b);
  std::array<double, 3> snapped = b;
  for (double& x : snapped) {
    if (x < kNearSide) x = 0;
  }
  snapped = clamp_barycentric(snapped);
  const double moved = (mesh.position(SurfacePoint::in_face(FaceId(face), b)) -
                        mesh.position(SurfacePoint::in_face(FaceId(face), snapped)))
                           .norm();
  if (moved > kSamePoint * mesh.diagonal()) {
    warnings.push_back(where + ": the landmark on mesh " + mesh.name + " is within " + number(kNearSide) +
                       " of its face's height from a side of face " + std::to_string(face) +
                       ": moved onto the side, by " + number(moved));
  }
  b = snapped;
  Token t;
  for (int k = 0; k < 3; ++k) {
    if (b[static_cast<size_t>(k)] == 1.0) {
      t.vertex = mesh.corner(face, k);
      return t;
    }
  }
  t.is_vertex = false;
  t.point = SurfacePoint::in_face(FaceId(face), b);
  return t;
}

/// Three comma-separated numbers, as in `0.2,0.3,0.5`; false if there are fewer than three fields.
/// \throw InvalidInputError naming the line if a field is not a number
bool parse_triple(const std::string& path, int line, const std::string& text, std::array<double, 3>& x) {
  size_t start = 0;
  for (size_t k = 0; k < 3; ++k) {
    const size_t end = k < 2 ? text.find(',', start) : text.size();
    if (end == std::string::npos) return false;
    const std::string field = text.substr(start, end - start);
    const auto [p, ec] = std::from_chars(field.data(), field.data() + field.size(), x[k]);
    if (field.empty() || ec == std::errc::invalid_argument || p != field.data() + field.size()) {
      fail(path, line, "'" + field + "' is not a number (in '" + text + "')");
    }
    if (ec == std::errc::result_out_of_range) fail(path, line, "'" + field + "' is out of range");
    start = end + 1;
  }
  return true;
}

/// Why b are not barycentric coordinates of a point of `face` (each finite, in [0, 1] and summing to 1, all within
/// kBarycentricTolerance), or "" if they are.
std::string barycentric_problem(const std::array<double, 3>& b, long long face) {
  double sum = 0;
  for (const double x : b) {
    if (!std::isfinite(x)) return "barycentric coordinate " + number(x) + " is not finite";
    if (x < -kBarycentricTolerance) {
      return "barycentric coordinate " + number(x) + " is negative: the point is outside face " + std::to_string(face);
    }
    if (x > 1 + kBarycentricTolerance) return "barycentric coordinate " + number(x) + " is greater than 1";
    sum += x;
  }
  if (std::abs(sum - 1) > kBarycentricTolerance) return "barycentric coordinates sum to " + number(sum) + ", not 1";
  return {};
}

Token parse_face_point(const std::string& path, int line, const std::string& token, const LandmarkMesh& mesh,
                       std::vector<std::string>& warnings) {
  const std::string form = "'f<face>:<b0>,<b1>,<b2>'";
  const size_t colon = token.find(':');
  if (colon == std::string::npos) fail(path, line, "'" + token + "' is not a face point " + form);
  const std::string face_text = token.substr(1, colon - 1);
  const bool digits = !face_text.empty() && face_text.find_first_not_of("0123456789") == std::string::npos;
  if (!digits) fail(path, line, "'" + face_text + "' in '" + token + "' is not a face index");
  long long face = 0;
  const auto [p, ec] = std::from_chars(face_text.data(), face_text.data() + face_text.size(), face);
  if (ec != std::errc() || face >= mesh.n_faces()) {
    fail(path, line,
         "face " + face_text + " is out of range for mesh " + mesh.name + " (" + std::to_string(mesh.n_faces()) +
             " faces)");
  }
  std::array<double, 3> b{};
  if (!parse_triple(path, line, token.substr(colon + 1), b)) {
    fail(path, line, "'" + token + "' is not a face point " + form + " (three barycentric coordinates)");
  }
  if (const std::string problem = barycentric_problem(b, face); !problem.empty()) fail(path, line, problem);
  return face_token(path + ":" + std::to_string(line), mesh, static_cast<int>(face), b, warnings);
}

Token parse_3d_point(const std::string& path, int line, const std::string& token, LandmarkMesh& mesh,
                     std::vector<std::string>& warnings) {
  std::array<double, 3> x{};
  if (!parse_triple(path, line, token, x)) fail(path, line, "'" + token + "' is not a 3D point 'x,y,z'");
  for (const double c : x) {
    if (!std::isfinite(c)) fail(path, line, "coordinate " + number(c) + " of '" + token + "' is not finite");
  }
  if (mesh.n_faces() == 0)
    fail(path, line, "mesh " + std::string(1, mesh.name) + " has no faces to locate " + token + " on");
  const NearestSurfacePoint near = mesh.nearest(Eigen::Vector3d(x[0], x[1], x[2]));
  if (near.distance > kFarFromSurface * mesh.diagonal()) {
    warnings.push_back(path + ":" + std::to_string(line) + ": the point " + token + " is " + number(near.distance) +
                       " from mesh " + mesh.name + " (" + number(100 * near.distance / mesh.diagonal()) +
                       "% of its bounding box diagonal); its nearest surface point is the landmark");
  }
  return face_token(path + ":" + std::to_string(line), mesh, near.face, near.bary, warnings);
}

/// One token of a pair line: a vertex index, a face point or a 3D point.
Token parse_token(const std::string& path, int line, const std::string& token, LandmarkMesh& mesh,
                  std::vector<std::string>& warnings) {
  if (token.find_first_not_of("0123456789") == std::string::npos) {
    Token t;
    const auto [p, ec] = std::from_chars(token.data(), token.data() + token.size(), t.vertex);
    if (ec != std::errc()) {
      fail(path, line,
           "vertex " + token + " is out of range for mesh " + mesh.name + " (" + std::to_string(mesh.n_vertices) +
               " vertices)");
    }
    return t;
  }
  const bool face = token[0] == 'f';
  const bool point = !face && token.find(',') != std::string::npos;
  if (token[0] == '-' && !point) fail(path, line, "negative vertex index '" + token + "' for mesh " + mesh.name);
  if ((face || point) && !mesh.has_geometry()) {
    fail(path, line, "'" + token + "' is a surface point; only vertex indices are accepted here");
  }
  if (face) return parse_face_point(path, line, token, mesh, warnings);
  if (point) return parse_3d_point(path, line, token, mesh, warnings);
  if (!mesh.has_geometry()) fail(path, line, "'" + token + "' is not a vertex index for mesh " + mesh.name);
  fail(path, line,
       "'" + token + "' is not a landmark of mesh " + mesh.name +
           ": expected a vertex index, a face point 'f<face>:<b0>,<b1>,<b2>' or a 3D point 'x,y,z'");
}

/// The checks every landmark pair passes, from a file or from arrays: indices in range, no point twice per side.
class LandmarkCollector {
 public:
  /// \param unit how messages call a pair's position: "line" (a file's line) or "row" (an array's row)
  LandmarkCollector(std::string name, std::string unit, const LandmarkMesh& a, const LandmarkMesh& b)
      : name_(std::move(name)), unit_(std::move(unit)), a_(a), b_(b) {}

  void add(const Token& a, const Token& b, int line) {
    lm_.a.push_back(point(a, a_, seen_a_, line));
    lm_.b.push_back(point(b, b_, seen_b_, line));
    lm_.line.push_back(line);
  }

  Landmarks finish() {
    if (lm_.a.size() < 2) {
      throw InvalidInputError(name_ + ": " + std::to_string(lm_.a.size()) + " landmark pair(s); at least 2 are needed");
    }
    return std::move(lm_);
  }

  std::vector<std::string>& warnings() { return lm_.warnings; }

 private:
  /// The landmarks of one side so far: vertices by index, and every landmark's position (with the meshes).
  struct Seen {
    std::map<int, int> line_of_vertex;
    struct Position {
      Eigen::Vector3d x;
      int line;
      bool is_vertex;
      double face_size;  ///< LandmarkMesh::face_size
    };
    std::vector<Position> positions;
  };

  [[noreturn]] void fail_at(int line, const std::string& what) const {
    if (unit_ == "line") fail(name_, line, what);
    throw InvalidInputError(name_ + ": " + unit_ + " " + std::to_string(line) + ": " + what);
  }

  SurfacePoint point(const Token& t, const LandmarkMesh& mesh, Seen& seen, int line) const {
    const std::string side(1, mesh.name);
    SurfacePoint p = t.point;
    if (t.is_vertex) {
      if (t.vertex < 0) fail_at(line, "negative vertex index '" + std::to_string(t.vertex) + "' for mesh " + side);
      if (t.vertex >= mesh.n_vertices) {
        fail_at(line, "vertex " + std::to_string(t.vertex) + " is out of range for mesh " + side + " (" +
                          std::to_string(mesh.n_vertices) + " vertices)");
      }
      const int v = static_cast<int>(t.vertex);
      if (auto [it, fresh] = seen.line_of_vertex.emplace(v, line); !fresh) {
        fail_at(line, "vertex " + std::to_string(v) + " of mesh " + side + " is already a landmark (" + unit_ + " " +
                          std::to_string(it->second) + ")");
      }
      p = SurfacePoint::at_vertex(VertexId(v));
    }
    if (!mesh.has_geometry()) return p;
    const Eigen::Vector3d x = mesh.position(p);
    const double size = mesh.face_size(p);
    // Two distinct vertices at one position are two landmarks (as before surface points existed).
    for (const auto& y : seen.positions) {
      const double distance = (x - y.x).norm();
      if (distance <= kSamePoint * mesh.diagonal() && !(t.is_vertex && y.is_vertex)) {
        fail_at(line, "the landmark " + landmark_token(p) + " of mesh " + side +
                          " is at the same point as the one of " + unit_ + " " + std::to_string(y.line));
      }
      if (const std::string why = too_close_to_cut(distance, size, y.face_size); !why.empty()) {
        fail_at(line, "the landmark " + landmark_token(p) + " of mesh " + side + " is " + number(distance) +
                          " from the one of " + unit_ + " " + std::to_string(y.line) + ", " + why);
      }
    }
    seen.positions.push_back({x, line, t.is_vertex, size});
    return p;
  }

  std::string name_, unit_;
  const LandmarkMesh& a_;
  const LandmarkMesh& b_;
  Seen seen_a_, seen_b_;
  Landmarks lm_;
};

Landmarks read_pairs(std::istream& in, const std::string& path, LandmarkMesh& a, LandmarkMesh& b) {
  LandmarkCollector collector(path, "line", a, b);
  std::string text;
  int line_no = 0;
  while (std::getline(in, text)) {
    ++line_no;
    if (line_no == 1) skip_byte_order_mark(text);
    for (char c : text) {
      const auto u = static_cast<unsigned char>(c);
      if (u == 0 || (u < 32 && c != '\t' && c != '\r')) fail(path, line_no, "not a text line (binary data?)");
    }
    if (const size_t hash = text.find('#'); hash != std::string::npos) text.resize(hash);
    std::istringstream tokens(text);
    std::vector<std::string> t;
    for (std::string s; tokens >> s;) t.push_back(s);
    if (t.empty()) continue;
    if (t.size() != 2) {
      fail(path, line_no,
           "expected two landmarks 'A B' (vertex indices, face points or 3D points), found " +
               std::to_string(t.size()) + " fields");
    }
    const Token ta = parse_token(path, line_no, t[0], a, collector.warnings());
    const Token tb = parse_token(path, line_no, t[1], b, collector.warnings());
    collector.add(ta, tb, line_no);
  }
  if (in.bad()) throw IoError(path + ": read error");
  return collector.finish();
}

std::ifstream open_landmarks(const std::string& path) { return open_input_file(path, "landmark file"); }

}  // namespace

Landmarks read_landmarks(const std::string& path, int n_vertices_a, int n_vertices_b) {
  std::ifstream in = open_landmarks(path);
  return read_landmarks(in, path, n_vertices_a, n_vertices_b);
}

Landmarks read_landmarks(std::istream& in, const std::string& path, int n_vertices_a, int n_vertices_b) {
  LandmarkMesh a('A', n_vertices_a), b('B', n_vertices_b);
  return read_pairs(in, path, a, b);
}

Landmarks read_landmarks(const std::string& path, const Eigen::MatrixXd& VA, const Eigen::MatrixXi& FA,
                         const Eigen::MatrixXd& VB, const Eigen::MatrixXi& FB) {
  std::ifstream in = open_landmarks(path);
  return read_landmarks(in, path, VA, FA, VB, FB);
}

Landmarks read_landmarks(std::istream& in, const std::string& name, const Eigen::MatrixXd& VA,
                         const Eigen::MatrixXi& FA, const Eigen::MatrixXd& VB, const Eigen::MatrixXi& FB) {
  LandmarkMesh a('A', VA, FA), b('B', VB, FB);
  return read_pairs(in, name, a, b);
}

Landmarks make_landmarks(const std::vector<std::array<long long, 2>>& pairs, const std::string& name, int n_vertices_a,
                         int n_vertices_b) {
  const LandmarkMesh a('A', n_vertices_a), b('B', n_vertices_b);
  LandmarkCollector collector(name, "row", a, b);
  for (size_t i = 0; i < pairs.size(); ++i) {
    Token ta, tb;
    ta.vertex = pairs[i][0];
    tb.vertex = pairs[i][1];
    collector.add(ta, tb, static_cast<int>(i));
  }
  return collector.finish();
}

Landmarks make_landmarks(const std::vector<SurfacePoint>& a, const std::vector<SurfacePoint>& b,
                         const std::string& name, const Eigen::MatrixXd& VA, const Eigen::MatrixXi& FA,
                         const Eigen::MatrixXd& VB, const Eigen::MatrixXi& FB) {
  if (a.size() != b.size()) {
    throw InvalidInputError(name + ": " + std::to_string(a.size()) + " landmarks on mesh A but " +
                            std::to_string(b.size()) + " on mesh B");
  }
  const LandmarkMesh mesh_a('A', VA, FA), mesh_b('B', VB, FB);
  LandmarkCollector collector(name, "row", mesh_a, mesh_b);
  const auto token = [&](const SurfacePoint& p, const LandmarkMesh& mesh, size_t row) {
    const std::string where = name + ": row " + std::to_string(row);
    Token t;
    if (p.kind == SurfacePoint::Kind::kVertex) {
      t.vertex = p.vertex.idx;
      return t;
    }
    if (p.kind != SurfacePoint::Kind::kFace) {
      throw InvalidInputError(where + ": the landmark on mesh " + mesh.name + " is not a vertex or a face point");
    }
    if (p.face.idx < 0 || p.face.idx >= mesh.n_faces()) {
      throw InvalidInputError(where + ": face " + std::to_string(p.face.idx) + " is out of range for mesh " +
                              mesh.name + " (" + std::to_string(mesh.n_faces()) + " faces)");
    }
    if (const std::string problem = barycentric_problem(p.bary, p.face.idx); !problem.empty()) {
      throw InvalidInputError(where + ": " + problem + " (mesh " + mesh.name + ")");
    }
    return face_token(where, mesh, p.face.idx, p.bary, collector.warnings());
  };
  for (size_t i = 0; i < a.size(); ++i) {
    const Token ta = token(a[i], mesh_a, i), tb = token(b[i], mesh_b, i);
    collector.add(ta, tb, static_cast<int>(i));
  }
  return collector.finish();
}

double face_size(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int face) {
  const Eigen::Vector3d a = V.row(F(face, 0)), b = V.row(F(face, 1)), c = V.row(F(face, 2));
  return std::sqrt(0.5 * (b - a).cross(c - a).norm());
}

std::string too_close_to_cut(double distance, double size_p, double size_q) {
  const double face = std::min(size_p, size_q);
  if (!std::isfinite(face) || !(distance < kTooClose * face)) return {};
  return "under " + number(kTooClose) + " of the size of their face (" + number(face) +
         "): too close to cut apart; move them apart or keep one";
}

void require_landmarks_apart(const std::vector<SurfacePoint>& points, const Eigen::MatrixXd& V,
                             const Eigen::MatrixXi& F, const std::string& name) {
  struct Placed {
    size_t index;
    Eigen::Vector3d x;
    double size;
  };
  const LandmarkMesh mesh(' ', V, F);
  std::vector<Placed> placed;
  for (size_t i = 0; i < points.size(); ++i) {
    const SurfacePoint& p = points[i];
    if (p.kind != SurfacePoint::Kind::kFace || p.face.idx < 0 || p.face.idx >= F.rows()) continue;
    if (!barycentric_problem(p.bary, p.face.idx).empty()) continue;  // the cut names it
    placed.push_back({i, mesh.position(p), mesh.face_size(p)});
  }
  for (size_t j = 0; j < placed.size(); ++j) {
    for (size_t i = 0; i < j; ++i) {
      const double distance = (placed[j].x - placed[i].x).norm();
      if (const std::string why = too_close_to_cut(distance, placed[i].size, placed[j].size); !why.empty()) {
        throw InvalidInputError(name + ": landmarks " + std::to_string(placed[i].index) + " and " +
                                std::to_string(placed[j].index) + " are " + number(distance) + " apart, " + why);
      }
    }
  }
}

std::string landmark_token(const SurfacePoint& p) {
  if (p.kind == SurfacePoint::Kind::kVertex) return std::to_string(p.vertex.idx);
  std::string token = "f" + std::to_string(p.face.idx) + ":";
  for (size_t k = 0; k < 3; ++k) {
    char s[32];
    const auto [end, ec] = std::to_chars(s, s + sizeof s, p.bary[k]);  // the shortest text that reads back exactly
    token.append(s, end);
    if (k < 2) token += ',';
  }
  return token;
}

void write_landmarks(const std::string& path, const Landmarks& landmarks) {
  OutputFile f(path);
  std::fprintf(f.get(), "# liftmap landmarks: point of A, point of B (vertex index or f<face>:<b0>,<b1>,<b2>)\n");
  for (size_t i = 0; i < landmarks.a.size(); ++i) {
    std::fprintf(f.get(), "%s %s\n", landmark_token(landmarks.a[i]).c_str(), landmark_token(landmarks.b[i]).c_str());
  }
  f.close();
}

}  // namespace liftmap
