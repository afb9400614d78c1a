#pragma once
// Helpers shared by the cut tests: loading the demo meshes, seeded landmark sets, and the invariant checks.

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "core/mesh.h"
#include "cut/cut_meshes.h"
#include "cut/geodesic_distance.h"
#include "io/read_mesh.h"

namespace liftmap::test {

inline TriangleMesh load(const std::string& name) {
  return read_mesh(std::string(LIFTMAP_DATA_DIR) + "/" + name + ".off");
}

inline double area(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  double a = 0;
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d p0 = V.row(F(f, 0)), p1 = V.row(F(f, 1)), p2 = V.row(F(f, 2));
    a += 0.5 * (p1 - p0).cross(p2 - p0).norm();
  }
  return a;
}

enum class Pattern { kRandom, kClose, kCollinear };

/// k distinct vertices: uniformly random, clustered in a few rings around one vertex, or along one edge path.
inline std::vector<VertexId> landmark_set(const TriangleMesh& m, int k, Pattern pattern, std::mt19937& rng) {
  const int n = static_cast<int>(m.V.rows());
  std::uniform_int_distribution<int> pick(0, n - 1);
  std::vector<int> pool;
  if (pattern == Pattern::kRandom) {
    for (int i = 0; i < n; ++i) pool.push_back(i);
  } else {
    const Mesh mesh(m.F, n);
    const VertexId s(pick(rng));
    const auto d = edge_graph_distances(mesh, m.V, s);
    std::vector<int> order(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) order[static_cast<size_t>(i)] = i;
    std::sort(order.begin(), order.end(),
              [&](int x, int y) { return d[static_cast<size_t>(x)] < d[static_cast<size_t>(y)]; });
    if (pattern == Pattern::kClose) {
      pool.assign(order.begin(), order.begin() + std::min(n, 3 * k));
    } else {
      // Vertices on the edge path from s to a far vertex: nearly collinear on the surface.
      const int target = order[static_cast<size_t>(n / 3)];
      int v = target;
      while (v != s.idx) {
        pool.push_back(v);
        int best = v;
        mesh.for_each_outgoing(VertexId(v), [&](HalfedgeId h) {
          const int w = mesh.head(h).idx;
          if (d[static_cast<size_t>(w)] < d[static_cast<size_t>(best)]) best = w;
        });
        v = best;
      }
      pool.push_back(s.idx);
      // Add random vertices if the path is too short.
      while (static_cast<int>(pool.size()) < k) pool.push_back(pick(rng));
    }
  }
  std::shuffle(pool.begin(), pool.end(), rng);
  std::vector<VertexId> out;
  std::set<int> used;
  for (const int v : pool) {
    if (static_cast<int>(out.size()) == k) break;
    if (used.insert(v).second) out.emplace_back(v);
  }
  while (static_cast<int>(out.size()) < k) {
    const int v = pick(rng);
    if (used.insert(v).second) out.emplace_back(v);
  }
  return out;
}

/// Counter-clockwise boundary loop of a disk (cut vertex ids).
inline std::vector<int> ccw_loop(const Mesh& cut) {
  const auto loops = cut.boundary_loops();
  std::vector<int> loop;
  for (const HalfedgeId h : loops.at(0)) loop.push_back(cut.head(h).idx);
  std::reverse(loop.begin(), loop.end());
  return loop;
}

/// Checks every invariant of one cut side; returns its cut mesh boundary loop.
inline void check_side(const CutSide& s, const TriangleMesh& in, const std::vector<SurfacePoint>& landmarks,
                       const std::vector<std::array<int, 2>>& tree, const std::string& what) {
  SCOPED_TRACE(what);
  const Mesh input(in.F, static_cast<int>(in.V.rows()));
  const double scale = (in.V.colwise().maxCoeff() - in.V.colwise().minCoeff()).norm();
  // The refined mesh is a closed genus-0 surface with the input's area.
  const Mesh refined(s.F, static_cast<int>(s.V.rows()));
  EXPECT_TRUE(refined.boundary_loops().empty());
  EXPECT_EQ(refined.euler_characteristic(), 2);
  EXPECT_NEAR(area(s.V, s.F), area(in.V, in.F), 1e-9 * area(in.V, in.F));
  // Every refined vertex lies on its recorded input face, and every refined face inside its input face.
  for (int v = 0; v < s.V.rows(); ++v) {
    const SurfacePoint& p = s.on_input[static_cast<size_t>(v)];
    ASSERT_EQ(p.kind, SurfacePoint::Kind::kFace);
    double sum = 0;
    for (const double b : p.bary) {
      EXPECT_GE(b, -1e-12);
      sum += b;
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
    EXPECT_LT((interpolate(input, in.V, p) - s.V.row(v)).norm(), 1e-9 * scale) << "refined vertex " << v;
  }
  for (int f = 0; f < s.F.rows(); ++f) {
    const auto fv = input.face_vertices(FaceId(s.face_to_input(f)));
    const Eigen::Vector3d a = in.V.row(fv[0].idx), b = in.V.row(fv[1].idx), c = in.V.row(fv[2].idx);
    const Eigen::Vector3d nrm = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = s.V.row(s.F(f, k));
      // Signed sub-areas: non-negative iff p is in the triangle (p is in its plane).
      const double wa = (b - p).cross(c - p).dot(nrm), wb = (c - p).cross(a - p).dot(nrm),
                   wc = (a - p).cross(b - p).dot(nrm);
      const double tol = 1e-9 * nrm.squaredNorm();
      EXPECT_TRUE(wa >= -tol && wb >= -tol && wc >= -tol) << "refined face " << f;
    }
  }
  // Input vertex i is refined vertex i; every landmark is a refined vertex at exactly its point.
  ASSERT_GE(s.V.rows(), in.V.rows());
  EXPECT_EQ(s.V.topRows(in.V.rows()), in.V);
  for (size_t i = 0; i < landmarks.size(); ++i) {
    EXPECT_LT((s.V.row(s.landmarks[i]) - interpolate(input, in.V, landmarks[i])).norm(), 1e-12 * scale)
        << "landmark " << i;
  }
  // Paths are simple, meet only at shared landmarks, pass through no other landmark.
  std::map<int, int> path_of;  // interior path vertex -> path
  std::set<int> lm(s.landmarks.begin(), s.landmarks.end());
  for (size_t e = 0; e < s.paths.size(); ++e) {
    const auto& p = s.paths[e];
    ASSERT_GE(p.size(), 2u);
    EXPECT_EQ(p.front(), s.landmarks[static_cast<size_t>(tree[e][1])]);
    EXPECT_EQ(p.back(), s.landmarks[static_cast<size_t>(tree[e][0])]);
    for (size_t i = 1; i + 1 < p.size(); ++i) {
      EXPECT_EQ(lm.count(p[i]), 0u) << "path " << e << " passes through a landmark";
      EXPECT_TRUE(path_of.emplace(p[i], static_cast<int>(e)).second) << "paths touch at vertex " << p[i];
    }
  }
  // The cut mesh is a disk.
  const Mesh cut(s.F_cut, static_cast<int>(s.cut_to_refined.size()));
  EXPECT_EQ(cut.boundary_loops().size(), 1u);
  EXPECT_EQ(cut.euler_characteristic(), 1);
}

/// Per landmark, the tree edges leaving it in counter-clockwise order (rotated to start at the smallest).
inline std::vector<std::vector<int>> rotation_system(const CutSide& s) {
  const Mesh refined(s.F, static_cast<int>(s.V.rows()));
  std::map<std::pair<int, int>, int> edge_path;
  for (size_t e = 0; e < s.paths.size(); ++e) {
    const auto& p = s.paths[e];
    for (size_t i = 0; i + 1 < p.size(); ++i) {
      edge_path[{std::min(p[i], p[i + 1]), std::max(p[i], p[i + 1])}] = static_cast<int>(e);
    }
  }
  std::vector<std::vector<int>> out;
  for (const int l : s.landmarks) {
    std::vector<int> order;
    refined.for_each_outgoing(VertexId(l), [&](HalfedgeId h) {
      const int w = refined.head(h).idx;
      const auto it = edge_path.find({std::min(l, w), std::max(l, w)});
      if (it != edge_path.end()) order.push_back(it->second);
    });
    if (!order.empty()) std::rotate(order.begin(), std::min_element(order.begin(), order.end()), order.end());
    out.push_back(order);
  }
  return out;
}

/// Checks both sides and nu.
inline void check_cut(const CutResult& r, const TriangleMesh& ma, const TriangleMesh& mb,
                      const std::vector<SurfacePoint>& la, const std::vector<SurfacePoint>& lb) {
  ASSERT_EQ(r.tree.size(), la.size() - 1);
  check_side(r.a, ma, la, r.tree, "mesh A");
  check_side(r.b, mb, lb, r.tree, "mesh B");
  // Same rotation system: the paths leave every landmark in the same cyclic order on both meshes.
  EXPECT_EQ(rotation_system(r.a), rotation_system(r.b));
  const Mesh cut_a(r.a.F_cut, static_cast<int>(r.a.cut_to_refined.size()));
  const Mesh cut_b(r.b.F_cut, static_cast<int>(r.b.cut_to_refined.size()));
  const auto loop_a = ccw_loop(cut_a), loop_b = ccw_loop(cut_b);
  ASSERT_EQ(r.nu.size(), loop_a.size());
  ASSERT_EQ(r.nu.size(), loop_b.size());
  // nu follows both loops in order (a bijection preserving the cyclic order).
  const size_t n = r.nu.size();
  const auto start_a = std::find(loop_a.begin(), loop_a.end(), r.nu[0][0]) - loop_a.begin();
  const auto start_b = std::find(loop_b.begin(), loop_b.end(), r.nu[0][1]) - loop_b.begin();
  for (size_t i = 0; i < n; ++i) {
    ASSERT_EQ(r.nu[i][0], loop_a[(static_cast<size_t>(start_a) + i) % n]);
    ASSERT_EQ(r.nu[i][1], loop_b[(static_cast<size_t>(start_b) + i) % n]);
  }
  // Landmark copies correspond to copies of the same landmark; each landmark has (tree degree) copies.
  std::map<int, int> lm_a, lm_b;
  for (size_t i = 0; i < r.a.landmarks.size(); ++i) lm_a[r.a.landmarks[i]] = static_cast<int>(i);
  for (size_t i = 0; i < r.b.landmarks.size(); ++i) lm_b[r.b.landmarks[i]] = static_cast<int>(i);
  std::vector<int> copies(la.size(), 0), degree(la.size(), 0);
  for (const auto& e : r.tree) ++degree[static_cast<size_t>(e[0])], ++degree[static_cast<size_t>(e[1])];
  for (const auto& pair : r.nu) {
    const auto ia = lm_a.find(r.a.cut_to_refined(pair[0]));
    const auto ib = lm_b.find(r.b.cut_to_refined(pair[1]));
    ASSERT_EQ(ia == lm_a.end(), ib == lm_b.end());
    if (ia != lm_a.end()) {
      ASSERT_EQ(ia->second, ib->second);
      ++copies[static_cast<size_t>(ia->second)];
    }
  }
  EXPECT_EQ(copies, degree);
}

inline void check_cut(const CutResult& r, const TriangleMesh& ma, const TriangleMesh& mb,
                      const std::vector<VertexId>& la, const std::vector<VertexId>& lb) {
  check_cut(r, ma, mb, vertex_points(la), vertex_points(lb));
}

struct Case {
  const char* a;
  const char* b;
};

/// Cuts meshes c.a and c.b with seeded landmark sets and checks every invariant.
inline void run(const Case& c, int k, Pattern pattern, unsigned seed, const CutOptions& options = {}) {
  const auto ma = load(c.a), mb = load(c.b);
  std::mt19937 rng(seed);
  const auto la = landmark_set(ma, k, pattern, rng);
  const auto lb = landmark_set(mb, k, pattern, rng);
  const std::string what = std::string(c.a) + "-" + c.b + " k=" + std::to_string(k) +
                           " pattern=" + std::to_string(static_cast<int>(pattern)) + " seed=" + std::to_string(seed);
  SCOPED_TRACE(what);
  try {
    const CutResult r = cut_meshes(ma.V, ma.F, mb.V, mb.F, la, lb, options);
    check_cut(r, ma, mb, la, lb);
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << ": " << e.what();
  }
}

}  // namespace liftmap::test
