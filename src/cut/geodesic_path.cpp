#include "cut/geodesic_path.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace liftmap {

namespace {

/// Fraction of a portal kept free at a blocked vertex: the path goes around it at this relative distance.
constexpr double kClearance = 0.05;
/// ... and at least at this fraction of the shortest edge of the input face the portal lies in. Without that floor
/// the clearance compounded: each straightening step passes around the vertex at 5% of the portal that the previous
/// step left (the edge from its own crossing to the vertex), and eight steps put cut vertices 1e-12 from a
/// landmark, whose disk faces could not be flattened (cow to triceratops with random landmarks; docs/algorithm.md,
/// "Clearance at a blocked vertex", for the measured choice of 5%).
constexpr double kMinClearance = 5e-2;
/// Crossings closer than this fraction of their edge to an unblocked end are snapped onto it (no slivers).
constexpr double kSnap = 0.02;

double cross2(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

/// The shortest edge of the input face that holds the refined face left of `h` (input vertices keep their ids in
/// the refinement).
double shortest_input_edge(const RefinedMesh& r, const Mesh& input, HalfedgeId h) {
  const FaceId f = r.mesh.face(h);
  if (!f.valid()) return 0;
  const auto v = input.face_vertices(FaceId(r.input_face[static_cast<size_t>(f.idx)]));
  const auto p = [&](int k) -> const Eigen::Vector3d& {
    return r.positions[static_cast<size_t>(v[static_cast<size_t>(k)].idx)];
  };
  return std::min({(p(1) - p(0)).norm(), (p(2) - p(1)).norm(), (p(0) - p(2)).norm()});
}

/// An edge of the strip that the path crosses: from `right` (a vertex of the old path) to `left`.
struct Portal {
  int right = -1, left = -1;  ///< refined vertex ids
  Eigen::Vector2d r, l;       ///< unfolded positions; `l` pulled toward `r` when `left` is blocked
  bool left_blocked = false;
  double open = 1;  ///< the fraction of the edge from `right` that the path may cross (`l` is there)
};

/// A point of the taut path: a vertex, or the point at parameter t from `right` to `left` on a strip edge.
struct Item {
  int vertex = -1;
  int right = -1, left = -1;
  double t = 0;
  [[nodiscard]] bool same(const Item& o) const {
    return vertex >= 0 ? vertex == o.vertex : (o.vertex < 0 && right == o.right && left == o.left && t == o.t);
  }
};

/// The strip of faces left of `path` (v0 -> vm), unfolded into the plane: its portals and the unfolded end.
/// Returns false if the strip cannot be built.
bool left_strip(const RefinedMesh& r, const Mesh& input, const std::vector<int>& path,
                const std::function<bool(int)>& blocked, std::vector<Portal>& portals, Eigen::Vector2d& end) {
  const Mesh& mesh = r.mesh;
  const auto pos = [&](int v) -> const Eigen::Vector3d& { return r.positions[static_cast<size_t>(v)]; };
  const size_t m = path.size() - 1;
  std::vector<HalfedgeId> e;
  for (size_t i = 0; i < m; ++i) {
    const HalfedgeId h = find_halfedge(mesh, VertexId(path[i]), VertexId(path[i + 1]));
    if (!h.valid() || mesh.is_boundary(h)) return false;
    e.push_back(h);
  }
  // Unfolded position of c in the counter-clockwise face (a, b, c).
  const auto third = [&](int a, const Eigen::Vector2d& pa, int b, const Eigen::Vector2d& pb, int c) {
    const double d = (pb - pa).norm();
    const double ac = (pos(c) - pos(a)).norm(), bc = (pos(c) - pos(b)).norm();
    const double x = (ac * ac - bc * bc + d * d) / (2 * d);
    const double y = std::sqrt(std::max(ac * ac - x * x, 0.0));
    const Eigen::Vector2d u = (pb - pa) / d;
    return Eigen::Vector2d(pa + x * u + y * Eigen::Vector2d(-u.y(), u.x()));
  };
  if (m == 1) {
    end = Eigen::Vector2d((pos(path[1]) - pos(path[0])).norm(), 0);
    return true;
  }
  // The current face of the walk: its three vertices with their unfolded positions.
  std::array<std::pair<int, Eigen::Vector2d>, 3> face;
  const auto at = [&](int v) -> const Eigen::Vector2d& {
    for (const auto& [id, p] : face) {
      if (id == v) return p;
    }
    return face[0].second;  // not reached: callers ask for vertices of the current face
  };
  // The face left of e0 is (v0, v1, w0), counter-clockwise.
  {
    const Eigen::Vector2d p0(0, 0), p1((pos(path[1]) - pos(path[0])).norm(), 0);
    const int w0 = mesh.head(mesh.next(e[0])).idx;
    face = {{{path[0], p0}, {path[1], p1}, {w0, third(path[0], p0, path[1], p1, w0)}}};
  }
  // Walk the fan of each inner path vertex v_i clockwise, from the face left of e_{i-1} to the face left of
  // e_i; each edge crossed on the way is a portal.
  size_t i = 1;
  HalfedgeId g = mesh.next(e[0]);
  for (int guard = 0; guard < 4 * mesh.n_halfedges(); ++guard) {
    if (g == e[i]) {
      if (i + 1 == path.size() - 1) {
        end = at(path.back());
        return true;
      }
      ++i;
      g = mesh.next(e[i - 1]);
      continue;
    }
    const int rv = mesh.tail(g).idx, lv = mesh.head(g).idx;
    Portal portal;
    portal.right = rv;
    portal.left = lv;
    portal.r = at(rv);
    portal.l = at(lv);
    portal.left_blocked = blocked(lv);
    if (portal.left_blocked) {
      const double length = (portal.l - portal.r).norm();
      const double kept_free =
          std::min(length, std::max(kClearance * length, kMinClearance * shortest_input_edge(r, input, g)));
      portal.open = length > 0 ? (length - kept_free) / length : 0.0;
      portal.l = portal.r + portal.open * (portal.l - portal.r);
    }
    portals.push_back(portal);
    // Cross g: the next face clockwise around rv is (lv, rv, c), counter-clockwise.
    if (mesh.is_boundary(Mesh::twin(g))) return false;
    const HalfedgeId g2 = mesh.next(Mesh::twin(g));
    const int c = mesh.head(g2).idx;
    // Copies, not references: `at` reads `face`, which is overwritten on the next line.
    const Eigen::Vector2d pl = at(lv), pr = at(rv);  // NOLINT(performance-unnecessary-copy-initialization)
    face = {{{lv, pl}, {rv, pr}, {c, third(lv, pl, rv, pr, c)}}};
    g = g2;
  }
  return false;
}

/// The shortest path through the portals from (0, 0) to `end` (simple stupid funnel algorithm), as items.
std::vector<Item> funnel(const std::vector<int>& path, const std::vector<Portal>& portals, const Eigen::Vector2d& end) {
  struct Pt {
    Eigen::Vector2d p;
    int id;
  };
  // ports[0] is the start, ports[n-1] the end; ports[j] for 1 <= j < n-1 is portals[j-1].
  std::vector<std::pair<Pt, Pt>> ports;  // (left, right)
  ports.push_back({{Eigen::Vector2d(0, 0), path.front()}, {Eigen::Vector2d(0, 0), path.front()}});
  for (size_t j = 0; j < portals.size(); ++j) {
    const Portal& q = portals[j];
    const int left_id = q.left_blocked ? -2 - static_cast<int>(j) : q.left;
    ports.push_back({{q.l, left_id}, {q.r, q.right}});
  }
  ports.push_back({{end, path.back()}, {end, path.back()}});
  const int n = static_cast<int>(ports.size());

  // Corners: (ports index, is left).
  std::vector<std::pair<int, bool>> corners{{0, false}};
  Pt apex = ports[0].first, left = apex, right = apex;
  int li = 0, ri = 0;
  for (int i = 1; i < n; ++i) {
    const Pt& pl = ports[static_cast<size_t>(i)].first;
    const Pt& pr = ports[static_cast<size_t>(i)].second;
    if (cross2(right.p - apex.p, pr.p - apex.p) >= 0) {
      if (apex.id == right.id || cross2(left.p - apex.p, pr.p - apex.p) < 0) {
        right = pr;
        ri = i;
      } else {
        if (li <= corners.back().first) return {};  // degenerate funnel: no progress, give up straightening
        corners.emplace_back(li, true);
        apex = left;
        right = left;
        ri = li;
        i = li;
        continue;
      }
    }
    if (cross2(left.p - apex.p, pl.p - apex.p) <= 0) {
      if (apex.id == left.id || cross2(right.p - apex.p, pl.p - apex.p) > 0) {
        left = pl;
        li = i;
      } else {
        if (ri <= corners.back().first) return {};
        corners.emplace_back(ri, false);
        apex = right;
        left = right;
        li = ri;
        i = ri;
        continue;
      }
    }
  }
  corners.emplace_back(n - 1, false);

  const auto point = [&](const std::pair<int, bool>& c) {
    const auto& port = ports[static_cast<size_t>(c.first)];
    return c.second ? port.first.p : port.second.p;
  };
  std::vector<Item> items;
  const auto add = [&](Item it) {
    if (items.empty() || !items.back().same(it)) items.push_back(it);
  };
  const auto edge_item = [&](const Portal& q, double t) {
    Item it;
    if (t < kSnap) {
      it.vertex = q.right;
    } else if (t > 1.0 - kSnap && !q.left_blocked) {
      it.vertex = q.left;
    } else {
      it.right = q.right;
      it.left = q.left;
      it.t = t;
    }
    return it;
  };
  const auto corner_item = [&](const std::pair<int, bool>& c) {
    const auto& port = ports[static_cast<size_t>(c.first)];
    const Pt& p = c.second ? port.first : port.second;
    if (p.id >= 0) {
      Item it;
      it.vertex = p.id;
      return it;
    }
    const Portal& q = portals[static_cast<size_t>(c.first - 1)];
    return edge_item(q, q.open);
  };
  add(corner_item(corners[0]));
  for (size_t k = 0; k + 1 < corners.size(); ++k) {
    const Eigen::Vector2d a = point(corners[k]), b = point(corners[k + 1]);
    for (int j = corners[k].first + 1; j < corners[k + 1].first; ++j) {
      const Portal& q = portals[static_cast<size_t>(j - 1)];
      // a + s (b - a) = q.r + u (q.l - q.r)
      const Eigen::Vector2d d1 = b - a, d2 = q.l - q.r;
      const double den = cross2(d1, d2);
      double u = std::abs(den) > 0 ? cross2(d1, a - q.r) / den : 0.0;
      u = std::clamp(u, 0.0, 1.0);
      add(edge_item(q, u * q.open));
    }
    add(corner_item(corners[k + 1]));
  }
  return items;
}

Eigen::Vector3d item_position(const RefinedMesh& r, const Item& it) {
  if (it.vertex >= 0) return r.positions[static_cast<size_t>(it.vertex)];
  return (1.0 - it.t) * r.positions[static_cast<size_t>(it.right)] + it.t * r.positions[static_cast<size_t>(it.left)];
}

double items_length(const RefinedMesh& r, const std::vector<Item>& items) {
  double l = 0;
  for (size_t i = 0; i + 1 < items.size(); ++i)
    l += (item_position(r, items[i + 1]) - item_position(r, items[i])).norm();
  return l;
}

/// The taut path on one side, or empty if it cannot be computed.
std::vector<Item> taut_side(const RefinedMesh& r, const Mesh& input, const std::vector<int>& path,
                            const std::function<bool(int)>& blocked) {
  std::vector<Portal> portals;
  Eigen::Vector2d end;
  if (!left_strip(r, input, path, blocked, portals, end)) return {};
  return funnel(path, portals, end);
}

}  // namespace

std::vector<int> shorten_path(RefinedMesh& refined, const Mesh& input, const std::vector<int>& path,
                              const std::function<bool(int)>& blocked) {
  if (path.size() < 3) return path;
  std::vector<Item> old_items(path.size());
  for (size_t i = 0; i < path.size(); ++i) old_items[i].vertex = path[i];
  const double old_length = items_length(refined, old_items);
  // The taut path of the side that gains more.
  std::vector<Item> best;
  double best_length = old_length;
  for (int side = 0; side < 2; ++side) {
    std::vector<int> p = path;
    if (side == 1) std::reverse(p.begin(), p.end());
    std::vector<Item> items = taut_side(refined, input, p, blocked);
    if (items.size() < 2) continue;
    if (side == 1) std::reverse(items.begin(), items.end());
    const double l = items_length(refined, items);
    if (l < best_length) {
      best_length = l;
      best = std::move(items);
    }
  }
  if (best.empty() || best_length > old_length * (1.0 - 1e-9)) return path;
  if (best.front().vertex != path.front() || best.back().vertex != path.back()) return path;
  std::vector<SurfacePoint> points;
  for (const Item& it : best) {
    if (it.vertex >= 0) {
      points.push_back(SurfacePoint::at_vertex(VertexId(it.vertex)));
      continue;
    }
    const HalfedgeId h = find_halfedge(refined.mesh, VertexId(it.right), VertexId(it.left));
    const EdgeId e = Mesh::edge(h);
    points.push_back(SurfacePoint::on_edge(e, h == Mesh::halfedge(e) ? it.t : 1.0 - it.t));
  }
  std::vector<int> ids = insert_polyline(refined, input, points);
  return ids.empty() ? path : ids;
}

}  // namespace liftmap
