#include "cut/trace_cut_paths.h"

#include "core/edge_graph_distance.h"

#include <algorithm>
#include <boost/heap/d_ary_heap.hpp>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <unordered_map>

#include "core/errors.h"
#include "core/parallel_for_each.h"
#include "cut/edge_key.h"
#include "cut/geodesic_path.h"

namespace liftmap {

namespace {

/// The tracing state of one mesh.
struct Side {
  RefinedMesh& refined;
  const Mesh& input;
  std::vector<int> landmark_of;                      ///< per refined vertex, landmark index or -1
  std::vector<char> on_tree;                         ///< per refined vertex
  std::unordered_map<std::uint64_t, int> tree_edge;  ///< refined edge -> tree edge index

  Side(RefinedMesh& r, const Mesh& in, const std::vector<int>& landmarks) : refined(r), input(in) {
    landmark_of.assign(static_cast<size_t>(r.n_vertices()), -1);
    for (size_t i = 0; i < landmarks.size(); ++i) landmark_of[static_cast<size_t>(landmarks[i])] = static_cast<int>(i);
    on_tree.assign(static_cast<size_t>(r.n_vertices()), 0);
  }
  void grow() {
    landmark_of.resize(static_cast<size_t>(refined.n_vertices()), -1);
    on_tree.resize(static_cast<size_t>(refined.n_vertices()), 0);
  }
  [[nodiscard]] bool is_tree_edge(int u, int w) const { return tree_edge.count(edge_key(u, w)) != 0; }
  [[nodiscard]] double length(int u, int w) const {
    return (refined.positions[static_cast<size_t>(u)] - refined.positions[static_cast<size_t>(w)]).norm();
  }

  /// Splits (at midpoints) the edges that could disconnect the surface left for the path from landmark vertex
  /// `c`. Seen on the surface cut along the tree (a disk): without chords (edges between two boundary
  /// vertices) the interior vertices of a triangulated disk are connected and every boundary vertex, hence every
  /// sector of the parent landmark, has an interior neighbour; a landmark not yet in the tree, adjacent to
  /// neither another landmark nor the tree, has a ring of ordinary vertices around it, so avoiding it cannot
  /// disconnect anything. Hence the edge-path search below always reaches every sector.
  void prepare(int c) {
    const Mesh& mesh = refined.mesh;
    const auto forbidden = [&](int v) {
      return landmark_of[static_cast<size_t>(v)] >= 0 && !on_tree[static_cast<size_t>(v)] && v != c;
    };
    std::vector<EdgeSplit> splits;
    for (int e = 0; e < mesh.n_edges(); ++e) {
      const HalfedgeId h = Mesh::halfedge(EdgeId(e));
      const int u = mesh.tail(h).idx, w = mesh.head(h).idx;
      if (is_tree_edge(u, w)) continue;
      const bool tu = on_tree[static_cast<size_t>(u)] != 0, tw = on_tree[static_cast<size_t>(w)] != 0;
      const bool lu = landmark_of[static_cast<size_t>(u)] >= 0, lw = landmark_of[static_cast<size_t>(w)] >= 0;
      if ((tu && tw) || (lu && lw) || (forbidden(u) && tw) || (forbidden(w) && tu)) splits.push_back({u, w, 0.5});
    }
    split_refined_mesh(refined, input, splits);
    grow();
  }

  /// The sector of tree vertex p that the edge p-w lies in: the tree edge met first turning counter-clockwise
  /// from p-w; -1 while p has no tree edge.
  [[nodiscard]] int sector(int p, int w) const {
    const Mesh& mesh = refined.mesh;
    const HalfedgeId h0 = find_halfedge(mesh, VertexId(p), VertexId(w));
    HalfedgeId h = h0;
    do {
      h = mesh.rotate_ccw(h);
      const auto it = tree_edge.find(edge_key(p, mesh.head(h).idx));
      if (it != tree_edge.end()) return it->second;
    } while (h != h0);
    return -1;
  }

  /// Shortest edge path from c to p through vertices that are neither on the tree nor landmarks, best per
  /// sector of p: sector -> (length, path from c to p).
  [[nodiscard]] std::map<int, std::pair<double, std::vector<int>>> shortest_paths(int c, int p) const {
    std::vector<double> dist;
    std::vector<int> pred;
    std::map<int, std::pair<double, int>> best;  // sector -> (length, last vertex before p)
    const auto relax = [&](int u, int w, double nd) {
      if (w == p) {  // arrivals at p are recorded per sector, not relaxed
        const int s = sector(p, u);
        auto it = best.find(s);
        if (it == best.end() || nd < it->second.first) best[s] = {nd, u};
        return false;
      }
      return !on_tree[static_cast<size_t>(w)] && landmark_of[static_cast<size_t>(w)] < 0;
    };
    edge_graph_search(
        refined.mesh, {c}, [&](int u, int w) { return length(u, w); }, relax, dist, &pred);
    std::map<int, std::pair<double, std::vector<int>>> out;
    for (const auto& [s, value] : best) {
      std::vector<int> path{p};
      for (int v = value.second; v >= 0; v = pred[static_cast<size_t>(v)]) path.push_back(v);
      std::reverse(path.begin(), path.end());
      out[s] = {value.first, std::move(path)};
    }
    return out;
  }

  /// The sector of tree vertex p that face f (incident to p) lies in; -1 while p has no tree edge.
  [[nodiscard]] int face_sector(int p, FaceId f) const {
    for (const HalfedgeId h : refined.mesh.face_halfedges(f)) {
      if (refined.mesh.tail(h).idx == p) return sector(p, refined.mesh.head(h).idx);
    }
    return -1;
  }

  /// Like `shortest_paths`, on the graph of vertices and `kSteiner` points per edge joined across faces, whose
  /// paths cross faces and come within a few percent of geodesics (closer in shape than edge paths, so that
  /// straightening ends in the right geodesic). Paths are returned as vertex and edge points of the refined mesh.
  [[nodiscard]] std::map<int, std::pair<double, std::vector<SurfacePoint>>> steiner_paths(int c, int p) const {
    constexpr int kSteiner = 4;
    const Mesh& mesh = refined.mesh;
    const int nv = mesh.n_vertices(), ne = mesh.n_edges();
    const auto n = static_cast<size_t>(nv + kSteiner * ne);
    std::vector<char> edge_blocked(static_cast<size_t>(ne), 0);
    for (int e = 0; e < ne; ++e) {
      const HalfedgeId h = Mesh::halfedge(EdgeId(e));
      edge_blocked[static_cast<size_t>(e)] = is_tree_edge(mesh.tail(h).idx, mesh.head(h).idx) ? 1 : 0;
    }
    // Every node's position, computed once: the search reads each node's many times (once per face around it
    // that a popped node shares, and again for its key).
    std::vector<Eigen::Vector3d> node_position(n);
    for (int v = 0; v < nv; ++v) node_position[static_cast<size_t>(v)] = refined.positions[static_cast<size_t>(v)];
    for (int e = 0; e < ne; ++e) {
      const HalfedgeId h = Mesh::halfedge(EdgeId(e));
      const Eigen::Vector3d& a = refined.positions[static_cast<size_t>(mesh.tail(h).idx)];
      const Eigen::Vector3d& b = refined.positions[static_cast<size_t>(mesh.head(h).idx)];
      for (int j = 0; j < kSteiner; ++j) {
        const double t = (j + 1.0) / (kSteiner + 1.0);
        node_position[static_cast<size_t>(nv + kSteiner * e + j)] = (1.0 - t) * a + t * b;
      }
    }
    const auto position = [&](int id) -> const Eigen::Vector3d& { return node_position[static_cast<size_t>(id)]; };
    const auto allowed = [&](int id) {
      if (id >= nv) return edge_blocked[static_cast<size_t>((id - nv) / kSteiner)] == 0;
      return id == c || (!on_tree[static_cast<size_t>(id)] && landmark_of[static_cast<size_t>(id)] < 0);
    };
    std::vector<FaceId> faces;
    const auto faces_of = [&](int id) {
      faces.clear();
      if (id < nv) {
        mesh.for_each_outgoing(VertexId(id), [&](HalfedgeId h) { faces.push_back(mesh.face(h)); });
      } else {
        const HalfedgeId h = Mesh::halfedge(EdgeId((id - nv) / kSteiner));
        faces.push_back(mesh.face(h));
        faces.push_back(mesh.face(Mesh::twin(h)));
      }
    };
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<double> dist(n, inf);
    std::vector<int> pred(n, -1);
    std::map<int, std::pair<double, int>> best;
    double best_any = inf;
    // Items (key, node), smallest first: every order of pops that respects this total order is the same, so the
    // heap's arity does not change the paths; four children per node make a pop cheaper than a binary heap's.
    using Item = std::pair<double, int>;
    boost::heap::d_ary_heap<Item, boost::heap::arity<4>, boost::heap::compare<std::greater<>>> queue;
    int n_sectors = 0;
    mesh.for_each_outgoing(VertexId(p), [&](HalfedgeId h) { n_sectors += is_tree_edge(p, mesh.head(h).idx) ? 1 : 0; });
    n_sectors = std::max(n_sectors, 1);
    // A* with the straight-line distance to p, a lower bound of the remaining length.
    const Eigen::Vector3d target = refined.positions[static_cast<size_t>(p)];
    const auto key = [&](int id, double d) { return d + (position(id) - target).norm(); };
    dist[static_cast<size_t>(c)] = 0;
    queue.emplace(key(c, 0.0), c);
    std::array<int, 3 + 3 * kSteiner> nodes{};
    while (!queue.empty()) {
      const auto [k_u, u] = queue.top();
      queue.pop();
      const double d = dist[static_cast<size_t>(u)];
      if (k_u > key(u, d) + 1e-12 * (1.0 + k_u)) continue;
      // All sectors reached, or far beyond the best arrival (other sectors are then not competitive; if the two
      // meshes share no reached sector, the caller falls back to the exhaustive edge-path search).
      if (static_cast<int>(best.size()) == n_sectors || k_u > 1.5 * best_any) break;
      const Eigen::Vector3d& pu = position(u);
      faces_of(u);
      for (const FaceId f : faces) {
        const auto fh = mesh.face_halfedges(f);
        size_t k = 0;
        for (const HalfedgeId h : fh) {
          nodes[k++] = mesh.tail(h).idx;
          const EdgeId e = Mesh::edge(h);
          for (int j = 0; j < kSteiner; ++j) nodes[k++] = nv + kSteiner * e.idx + j;
        }
        for (const int w : nodes) {
          if (w == u) continue;
          const double nd = d + (position(w) - pu).norm();
          if (w == p) {
            const int s = face_sector(p, f);
            const auto it = best.find(s);
            if (it == best.end() || nd < it->second.first) best[s] = {nd, u};
            best_any = std::min(best_any, nd);
            continue;
          }
          if (!allowed(w)) continue;
          if (nd < dist[static_cast<size_t>(w)]) {
            dist[static_cast<size_t>(w)] = nd;
            pred[static_cast<size_t>(w)] = u;
            queue.emplace(key(w, nd), w);
          }
        }
      }
    }
    const auto point = [&](int id) {
      if (id < nv) return SurfacePoint::at_vertex(VertexId(id));
      return SurfacePoint::on_edge(EdgeId((id - nv) / kSteiner), ((id - nv) % kSteiner + 1.0) / (kSteiner + 1.0));
    };
    std::map<int, std::pair<double, std::vector<SurfacePoint>>> out;
    for (const auto& [s, value] : best) {
      std::vector<SurfacePoint> path{point(p)};
      for (int v = value.second; v >= 0; v = pred[static_cast<size_t>(v)]) path.push_back(point(v));
      std::reverse(path.begin(), path.end());
      out[s] = {value.first, std::move(path)};
    }
    return out;
  }

  /// True if `path` (c to p) is a valid new tree path entering p in sector `s`.
  [[nodiscard]] bool valid_path(const std::vector<int>& path, int s) const {
    if (path.size() < 2) return false;
    std::vector<int> sorted(path);
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return false;
    for (size_t i = 1; i + 1 < path.size(); ++i) {
      const auto v = static_cast<size_t>(path[i]);
      if (on_tree[v] || landmark_of[v] >= 0) return false;
    }
    for (size_t i = 0; i + 1 < path.size(); ++i) {
      if (!find_halfedge(refined.mesh, VertexId(path[i]), VertexId(path[i + 1])).valid()) return false;
    }
    return sector(path.back(), path[path.size() - 2]) == s;
  }

  void add_to_tree(const std::vector<int>& path, int edge_index) {
    for (const int v : path) on_tree[static_cast<size_t>(v)] = 1;
    for (size_t i = 0; i + 1 < path.size(); ++i) tree_edge[edge_key(path[i], path[i + 1])] = edge_index;
  }

  /// Straightens `path` toward a geodesic without leaving the sector: repeated `shorten_path` steps while they
  /// gain more than `kMinGain` of the length, at most `kMaxSteps`; a step that would break a tree condition is
  /// undone and ends the straightening.
  std::vector<int> shorten(const std::vector<int>& path, int s) {
    const auto blocked = [&](int v) {
      return on_tree[static_cast<size_t>(v)] != 0 || landmark_of[static_cast<size_t>(v)] >= 0;
    };
    std::vector<int> current = path;
    constexpr int kMaxSteps = 8;
    constexpr double kMinGain = 1e-3;
    for (int step = 0; step < kMaxSteps; ++step) {
      // A rejected attempt must leave no trace: its insertion could have split edges of the current path.
      RefinedMesh saved = refined;
      std::vector<int> next = shorten_path(refined, input, current, blocked);
      grow();
      if (!valid_path(next, s)) {
        refined = std::move(saved);
        break;
      }
      const double before = path_length(current), after = path_length(next);
      current = std::move(next);
      if (after > before * (1.0 - kMinGain)) break;
    }
    return current;
  }
  [[nodiscard]] double path_length(const std::vector<int>& path) const {
    double l = 0;
    for (size_t i = 0; i + 1 < path.size(); ++i) l += length(path[i], path[i + 1]);
    return l;
  }
};

}  // namespace

TracedPaths trace_cut_paths(RefinedMesh& a, const Mesh& input_a, const std::vector<int>& landmarks_a, RefinedMesh& b,
                            const Mesh& input_b, const std::vector<int>& landmarks_b,
                            const std::vector<std::array<int, 2>>& tree, const TraceOptions& options) {
  std::array<Side, 2> sides{Side(a, input_a, landmarks_a), Side(b, input_b, landmarks_b)};
  const std::array<const std::vector<int>*, 2> landmarks{&landmarks_a, &landmarks_b};
  TracedPaths out;
  for (size_t e = 0; e < tree.size(); ++e) {
    const int parent = tree[e][0], child = tree[e][1];
    std::array<int, 2> c{}, p{};
    for (size_t s = 0; s < 2; ++s) {
      c[s] = (*landmarks[s])[static_cast<size_t>(child)];
      p[s] = (*landmarks[s])[static_cast<size_t>(parent)];
    }
    // Candidate paths per sector of the parent landmark, on both meshes; the sector reached on both with the
    // least total length wins.
    std::array<std::map<int, std::pair<double, std::vector<SurfacePoint>>>, 2> candidates;
    const auto choose = [&]() {
      int best_sector = -2;
      double best_length = std::numeric_limits<double>::infinity();
      for (const auto& [sector, value] : candidates[0]) {
        const auto it = candidates[1].find(sector);
        if (it != candidates[1].end() && value.first + it->second.first < best_length) {
          best_length = value.first + it->second.first;
          best_sector = sector;
        }
      }
      return best_sector;
    };
    const auto edge_paths = [&](size_t s) {
      std::map<int, std::pair<double, std::vector<SurfacePoint>>> out_s;
      for (auto& [sector, value] : sides[s].shortest_paths(c[s], p[s])) {
        std::vector<SurfacePoint> points;
        for (const int v : value.second) points.push_back(SurfacePoint::at_vertex(VertexId(v)));
        out_s[sector] = {value.first, std::move(points)};
      }
      return out_s;
    };
    // The two meshes' steps for a tree edge are independent: one thread each where two are available.
    parallel_for_each(2, 2, [&](int i) {
      const auto s = static_cast<size_t>(i);
      sides[s].prepare(c[s]);
      candidates[s] = options.steiner ? sides[s].steiner_paths(c[s], p[s]) : edge_paths(s);
    });
    int sector = choose();
    if (sector == -2 && options.steiner) {
      for (size_t s = 0; s < 2; ++s) candidates[s] = edge_paths(s);
      sector = choose();
    }
    if (sector == -2) {
      throw PipelineError("cut: no consistent path for tree edge (landmark " + std::to_string(parent) + ", landmark " +
                          std::to_string(child) + ")");
    }
    std::array<std::vector<int>, 2> paths;
    parallel_for_each(2, 2, [&](int i) {
      const auto s = static_cast<size_t>(i);
      Side& side = sides[s];
      RefinedMesh before = side.refined;
      paths[s] = insert_polyline(side.refined, side.input, candidates[s][sector].second);
      side.grow();
      if (!side.valid_path(paths[s], sector)) {
        // Fall back to the edge path on the prepared surface, which cannot fail (see `prepare`).
        side.refined = std::move(before);
        auto fallback = edge_paths(s);
        if (fallback.count(sector) == 0) {
          throw PipelineError("cut: sector " + std::to_string(sector) + " of landmark " + std::to_string(parent) +
                              " cannot be reached");
        }
        paths[s] = insert_polyline(side.refined, side.input, fallback[sector].second);
      }
      if (options.shorten) paths[s] = side.shorten(paths[s], sector);
      side.add_to_tree(paths[s], static_cast<int>(e));
    });
    out.edges.push_back(tree[e]);
    out.paths_a.push_back(std::move(paths[0]));
    out.paths_b.push_back(std::move(paths[1]));
  }
  return out;
}

}  // namespace liftmap
