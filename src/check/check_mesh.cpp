#include "check/check_mesh.h"

#include <nlohmann/json.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <tuple>

#include "core/errors.h"
#include "core/mesh.h"

namespace liftmap {

namespace {

constexpr int kMaxExamples = 5;
// A face is degenerate when its height over its longest edge is below this fraction of that edge: its
// Jacobian (paper §3.3) is then numerically singular.
constexpr double kDegenerateRatio = 1e-10;

class UnionFind {
 public:
  explicit UnionFind(int n) : parent_(static_cast<size_t>(n)) { std::iota(parent_.begin(), parent_.end(), 0); }
  int find(int x) {
    while (parent_[static_cast<size_t>(x)] != x) {
      parent_[static_cast<size_t>(x)] = parent_[static_cast<size_t>(parent_[static_cast<size_t>(x)])];
      x = parent_[static_cast<size_t>(x)];
    }
    return x;
  }
  void unite(int a, int b) { parent_[static_cast<size_t>(find(a))] = find(b); }

 private:
  std::vector<int> parent_;
};

class ProblemList {
 public:
  void add(const std::string& kind, const std::string& example) {
    auto it = std::find_if(problems_.begin(), problems_.end(), [&](const MeshProblem& p) { return p.kind == kind; });
    if (it == problems_.end()) {
      problems_.push_back({kind, 0, {}});
      it = problems_.end() - 1;
    }
    ++it->count;
    if (static_cast<int>(it->examples.size()) < kMaxExamples) it->examples.push_back(example);
  }
  std::vector<MeshProblem> take() { return std::move(problems_); }

 private:
  std::vector<MeshProblem> problems_;
};

struct Corner {
  int lo, hi, face, k;
};

/// Coordinates the pipeline cannot compute with (CoordinateLimits): too large, too small, too far from the
/// origin for the mesh's size, or edges too short for it.
void check_coordinate_ranges(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<char>& usable,
                             ProblemList& problems) {
  if (V.rows() == 0 || !V.allFinite()) return;  // non-finite coordinates are reported on their own
  Eigen::Index v_max = 0, c_max = 0;
  const double magnitude = V.cwiseAbs().maxCoeff(&v_max, &c_max);
  const double diagonal = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  if (magnitude > CoordinateLimits::kMaxMagnitude) {
    problems.add("coordinate out of range", "vertex " + std::to_string(v_max) + " has coordinate " +
                                                figure(V(v_max, c_max)) + ", beyond +-" +
                                                figure(CoordinateLimits::kMaxMagnitude) + ": scale the mesh down");
    return;
  }
  if (diagonal < CoordinateLimits::kMinDiagonal) {
    problems.add("coordinate out of range", "the bounding box diagonal " + figure(diagonal) + " is below " +
                                                figure(CoordinateLimits::kMinDiagonal) + ": scale the mesh up");
    return;
  }
  if (magnitude > CoordinateLimits::kMaxOffset * diagonal) {
    problems.add("mesh far from the origin",
                 "vertex " + std::to_string(v_max) + " has coordinate " + figure(V(v_max, c_max)) + ", " +
                     figure(magnitude / diagonal) + " times the bounding box diagonal " + figure(diagonal) +
                     " (at most " + figure(CoordinateLimits::kMaxOffset) +
                     "): too few digits are left for the shape; translate the mesh towards the origin");
  }
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    if (!usable[static_cast<size_t>(f)]) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      const double length = (V.row(a) - V.row(b)).norm();
      if (length > 0 && length < CoordinateLimits::kMinEdgeRatio * diagonal && a < b) {
        problems.add("edge too short for the mesh's extent",
                     "edge " + edge_name(a, b) + " has length " + figure(length) + ", " + figure(length / diagonal) +
                         " of the bounding box diagonal (at least " + figure(CoordinateLimits::kMinEdgeRatio) + ")");
      }
    }
  }
}

}  // namespace

std::string MeshReport::summary() const {
  std::ostringstream s;
  for (size_t i = 0; i < problems.size(); ++i) {
    const MeshProblem& p = problems[i];
    if (i > 0) s << "; ";
    s << p.examples.front();
    if (p.count > 1) s << " (and " << p.count - 1 << " more " << p.kind << (p.count > 2 ? "s" : "") << ")";
  }
  return s.str();
}

MeshReport check_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  MeshReport r;
  ProblemList problems;
  const int nv = static_cast<int>(V.rows());
  const int nf = static_cast<int>(F.rows());
  r.n_vertices = nv;
  r.n_faces = nf;

  for (int v = 0; v < nv; ++v) {
    if (!V.row(v).allFinite()) {
      std::ostringstream s;
      s << "vertex " << v << " has a non-finite coordinate (" << V(v, 0) << ", " << V(v, 1) << ", " << V(v, 2) << ")";
      problems.add("non-finite coordinate", s.str());
    }
  }

  // Faces that cannot be part of any mesh structure are reported and left out of the topology below.
  std::vector<char> usable(static_cast<size_t>(nf), 1);
  std::vector<char> referenced(static_cast<size_t>(nv), 0);
  for (int f = 0; f < nf; ++f) {
    const int a = F(f, 0), b = F(f, 1), c = F(f, 2);
    if (std::min({a, b, c}) < 0 || std::max({a, b, c}) >= nv) {
      problems.add("face with an invalid index",
                   "face " + std::to_string(f) + " references a vertex outside 0.." + std::to_string(nv - 1));
      usable[static_cast<size_t>(f)] = 0;
      continue;
    }
    referenced[static_cast<size_t>(a)] = referenced[static_cast<size_t>(b)] = referenced[static_cast<size_t>(c)] = 1;
    if (a == b || b == c || c == a) {
      problems.add("degenerate face", "face " + std::to_string(f) + " repeats a vertex (" + std::to_string(a) + ", " +
                                          std::to_string(b) + ", " + std::to_string(c) + ")");
      usable[static_cast<size_t>(f)] = 0;
      continue;
    }
    const Eigen::Vector3d p = V.row(a), q = V.row(b), w = V.row(c);
    const double twice_area = (q - p).cross(w - p).norm();
    const double longest = std::max({(q - p).norm(), (w - q).norm(), (p - w).norm()});
    if (std::isfinite(twice_area) && twice_area <= kDegenerateRatio * longest * longest) {
      std::ostringstream s;
      s << "face " << f << " (" << a << ", " << b << ", " << c << ") has zero or near-zero area (" << twice_area / 2
        << ")";
      problems.add("degenerate face", s.str());
    }
  }
  int n_referenced = 0;
  for (int v = 0; v < nv; ++v) {
    if (referenced[static_cast<size_t>(v)]) {
      ++n_referenced;
    } else {
      problems.add("unreferenced vertex", "vertex " + std::to_string(v) + " is used by no face");
    }
  }

  // Edges, from the sorted list of face corners.
  std::vector<Corner> corners;
  corners.reserve(static_cast<size_t>(3 * nf));
  for (int f = 0; f < nf; ++f) {
    if (!usable[static_cast<size_t>(f)]) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      corners.push_back({std::min(a, b), std::max(a, b), f, k});
    }
  }
  std::sort(corners.begin(), corners.end(), [](const Corner& x, const Corner& y) {
    return std::tie(x.lo, x.hi, x.face) < std::tie(y.lo, y.hi, y.face);
  });
  UnionFind components(nv);
  UnionFind fans(3 * nf);  // corners around one vertex joined across shared edges
  auto corner_at = [&](int f, int v) {
    for (int k = 0; k < 3; ++k) {
      if (F(f, k) == v) return 3 * f + k;
    }
    return -1;
  };
  bool manifold = true;
  for (size_t i = 0; i < corners.size();) {
    size_t j = i + 1;
    while (j < corners.size() && corners[j].lo == corners[i].lo && corners[j].hi == corners[i].hi) ++j;
    const Corner& c0 = corners[i];
    ++r.n_edges;
    components.unite(c0.lo, c0.hi);
    const auto n = static_cast<int>(j - i);
    if (n == 1) {
      ++r.n_boundary_edges;
      problems.add("boundary edge", "edge " + edge_name(c0.lo, c0.hi) + " has only one face (the mesh is open)");
    } else if (n > 2) {
      manifold = false;
      problems.add("non-manifold edge",
                   "edge " + edge_name(c0.lo, c0.hi) + " is shared by " + std::to_string(n) + " faces");
    } else {
      const Corner& c1 = corners[i + 1];
      if (F(c0.face, c0.k) == F(c1.face, c1.k)) {
        manifold = false;
        const bool same_face_set = [&] {
          std::array<int, 3> x{F(c0.face, 0), F(c0.face, 1), F(c0.face, 2)};
          std::array<int, 3> y{F(c1.face, 0), F(c1.face, 1), F(c1.face, 2)};
          std::sort(x.begin(), x.end());
          std::sort(y.begin(), y.end());
          return x == y;
        }();
        if (!same_face_set) {
          problems.add("inconsistent orientation",
                       "faces " + std::to_string(c0.face) + " and " + std::to_string(c1.face) +
                           " disagree on orientation across edge " + edge_name(c0.lo, c0.hi));
        }
      }
    }
    for (size_t a = i + 1; a < j; ++a) {
      fans.unite(corner_at(corners[i].face, c0.lo), corner_at(corners[a].face, c0.lo));
      fans.unite(corner_at(corners[i].face, c0.hi), corner_at(corners[a].face, c0.hi));
    }
    i = j;
  }

  // Duplicate faces: the same three vertices, in any order.
  {
    std::vector<std::pair<std::array<int, 3>, int>> keys;
    for (int f = 0; f < nf; ++f) {
      if (!usable[static_cast<size_t>(f)]) continue;
      std::array<int, 3> k{F(f, 0), F(f, 1), F(f, 2)};
      std::sort(k.begin(), k.end());
      keys.emplace_back(k, f);
    }
    std::sort(keys.begin(), keys.end());
    for (size_t i = 1; i < keys.size(); ++i) {
      if (keys[i].first == keys[i - 1].first) {
        manifold = false;
        problems.add("duplicate face", "faces " + std::to_string(keys[i - 1].second) + " and " +
                                           std::to_string(keys[i].second) + " have the same vertices");
      }
    }
  }

  // Non-manifold vertices: the faces around a vertex must form one fan.
  {
    std::vector<int> first_root(static_cast<size_t>(nv), -1);
    std::vector<char> reported(static_cast<size_t>(nv), 0);
    for (int f = 0; f < nf; ++f) {
      if (!usable[static_cast<size_t>(f)]) continue;
      for (int k = 0; k < 3; ++k) {
        const auto v = static_cast<size_t>(F(f, k));
        const int root = fans.find(3 * f + k);
        if (first_root[v] < 0) {
          first_root[v] = root;
        } else if (first_root[v] != root && !reported[v]) {
          reported[v] = 1;
          manifold = false;
          problems.add("non-manifold vertex", "vertex " + std::to_string(v) +
                                                  " joins separate fans of faces (e.g. two cones touching at a tip)");
        }
      }
    }
  }

  for (int v = 0; v < nv; ++v) {
    if (referenced[static_cast<size_t>(v)] && components.find(v) == v) ++r.n_components;
  }
  r.euler_characteristic = n_referenced - r.n_edges + nf;

  if (manifold && std::all_of(usable.begin(), usable.end(), [](char u) { return u != 0; })) {
    try {
      const Mesh mesh(F, nv);
      r.n_boundary_loops = static_cast<int>(mesh.boundary_loops().size());
      // chi = sum over components of (2 - 2 g_i - b_i)
      r.genus = (2 * r.n_components - *r.n_boundary_loops - r.euler_characteristic) / 2;
    } catch (const InvalidInputError& e) {
      problems.add("non-manifold configuration", e.what());
    }
  }

  if (nf == 0) problems.add("empty mesh", "the mesh has no faces");
  if (r.n_components > 1) {
    problems.add("disconnected mesh", std::to_string(r.n_components) +
                                          " connected components: only a single connected surface can be mapped");
  }
  if (r.n_boundary_loops.value_or(0) > 0) {
    problems.add("open mesh",
                 std::to_string(*r.n_boundary_loops) + " boundary loop(s): only closed surfaces can be mapped");
  }
  if (r.genus && *r.genus != 0) {
    problems.add("wrong genus", "genus " + std::to_string(*r.genus) + ": only genus 0 is supported");
  }
  // The orientation of the whole surface is only defined once it is closed and consistently oriented.
  if (r.genus && r.n_boundary_loops == 0 && r.n_components == 1 && V.allFinite()) {
    const double volume = signed_volume(V, F);
    if (volume < 0) {
      problems.add("inside-out mesh", "the faces are oriented inward (signed volume " + figure(volume) +
                                          " < 0): reverse the vertex order of every face");
    }
  }
  check_coordinate_ranges(V, F, usable, problems);
  r.problems = problems.take();
  return r;
}

double signed_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  // About the bounding box centre, so that a translation does not cost digits.
  const Eigen::RowVector3d centre = 0.5 * (V.colwise().maxCoeff() + V.colwise().minCoeff());
  double sum = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d p = (V.row(F(f, 0)) - centre).transpose();
    const Eigen::Vector3d q = (V.row(F(f, 1)) - centre).transpose();
    const Eigen::Vector3d w = (V.row(F(f, 2)) - centre).transpose();
    sum += p.dot(q.cross(w));
  }
  return sum / 6;
}

nlohmann::json mesh_report_json(const MeshReport& r, const std::string& name) {
  nlohmann::json j;
  j["mesh"] = name;
  j["vertices"] = r.n_vertices;
  j["faces"] = r.n_faces;
  j["edges"] = r.n_edges;
  j["connected_components"] = r.n_components;
  j["boundary_edges"] = r.n_boundary_edges;
  j["boundary_loops"] = r.n_boundary_loops ? nlohmann::json(*r.n_boundary_loops) : nlohmann::json(nullptr);
  j["euler_characteristic"] = r.euler_characteristic;
  j["genus"] = r.genus ? nlohmann::json(*r.genus) : nlohmann::json(nullptr);
  j["mappable"] = r.mappable();
  j["problems"] = nlohmann::json::array();
  for (const auto& p : r.problems)
    j["problems"].push_back({{"kind", p.kind}, {"count", p.count}, {"examples", p.examples}});
  return j;
}

std::optional<double> reverse_if_inside_out(const Eigen::MatrixXd& V, Eigen::MatrixXi& F) {
  if (F.rows() == 0 || F.minCoeff() < 0 || F.maxCoeff() >= V.rows() || !V.allFinite()) return std::nullopt;
  const double volume = signed_volume(V, F);
  if (!(volume < 0)) return std::nullopt;
  F.col(1).swap(F.col(2));
  return volume;
}

void require_mappable(const MeshReport& report, const std::string& path) {
  if (!report.mappable()) throw InvalidInputError(path + ": cannot be mapped: " + report.summary());
}

}  // namespace liftmap
