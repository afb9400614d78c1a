#include "lift_fixtures.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <queue>
#include <stdexcept>
#include <utility>

#include "flatten/boundary_loop.h"
#include "flatten/tutte.h"
#include "lift/exact_predicates.h"

namespace liftmap::testing {

namespace {

/// Deterministic value in [-1, 1] from two integers.
double hash_unit(int i, int j) {
  std::uint64_t x =
      static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ULL ^ static_cast<std::uint64_t>(j + 7) * 0xC2B2AE3D27D4EB4FULL;
  x ^= x >> 31;
  x *= 0xBF58476D1CE4E5B9ULL;
  x ^= x >> 29;
  return static_cast<double>(x % 2000001ULL) / 1000000.0 - 1.0;
}

Eigen::MatrixXi grid_faces(int nx, int ny, bool alternate, bool slash) {
  Eigen::MatrixXi F(2 * nx * ny, 3);
  auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  int f = 0;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const bool s = alternate ? (i + j) % 2 == 0 : slash;
      if (s) {
        F.row(f++) << id(i, j), id(i + 1, j), id(i + 1, j + 1);
        F.row(f++) << id(i, j), id(i + 1, j + 1), id(i, j + 1);
      } else {
        F.row(f++) << id(i, j), id(i + 1, j), id(i, j + 1);
        F.row(f++) << id(i + 1, j), id(i + 1, j + 1), id(i, j + 1);
      }
    }
  }
  return F;
}

/// A set of faces of a closed mesh that stays a disk while it grows.
class PatchGrower {
 public:
  explicit PatchGrower(const TriangleMesh& whole)
      : whole_(whole),
        mesh_(whole.F, static_cast<int>(whole.V.rows())),
        in_(mesh_.n_faces(), 0),
        uses_(mesh_.n_vertices(), 0) {}

  /// Adds faces in order of geodesic distance (Dijkstra along edges) from the seed face, each as soon as it
  /// keeps the patch a disk, until `n_faces`: a roughly round patch.
  void grow(int seed, int n_faces) {
    VertexData<double> dist(mesh_.n_vertices(), std::numeric_limits<double>::infinity());
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> heap;
    for (VertexId v : mesh_.face_vertices(FaceId(seed))) {
      dist[v] = 0;
      heap.emplace(0.0, v.idx);
    }
    while (!heap.empty()) {
      const auto [d, i] = heap.top();
      heap.pop();
      if (d > dist[VertexId(i)]) continue;
      mesh_.for_each_outgoing(VertexId(i), [&](HalfedgeId h) {
        const VertexId w = mesh_.head(h);
        const double dw = d + (whole_.V.row(i) - whole_.V.row(w.idx)).norm();
        if (dw < dist[w]) {
          dist[w] = dw;
          heap.emplace(dw, w.idx);
        }
      });
    }
    auto face_distance = [&](FaceId f) {
      double d = 0;
      for (VertexId v : mesh_.face_vertices(f)) d = std::max(d, dist[v]);
      return d;
    };
    // Always the closest face that keeps a disk; a blocked face comes back when a neighbour is added.
    std::priority_queue<Item, std::vector<Item>, std::greater<>> front;
    front.emplace(0.0, seed);
    while (count_ < n_faces && !front.empty()) {
      const FaceId f(front.top().second);
      front.pop();
      if (in_[f] || (count_ > 0 && !can_add(f))) continue;
      add(f);
      for (HalfedgeId h : mesh_.face_halfedges(f)) {
        const FaceId g = mesh_.face(Mesh::twin(h));
        if (g.valid() && !in_[g]) front.emplace(face_distance(g), g.idx);
      }
    }
  }

  /// Adds every face that shares two edges with the patch (closing notches), until none is left: a rounder
  /// boundary without ears, so that the Tutte embedding has no long chords.
  void fill_notches() {
    for (bool added = true; added;) {
      added = false;
      for (int i = 0; i < mesh_.n_faces(); ++i) {
        VertexId opposite;
        if (!in_[FaceId(i)] && shared(FaceId(i), &opposite) == 2) {
          add(FaceId(i));
          added = true;
        }
      }
    }
  }

  /// Removes patch faces with two boundary edges (ears), until none is left: in a Tutte embedding on a circle an
  /// ear is a sliver between three consecutive boundary points.
  void trim_ears() {
    for (bool removed = true; removed;) {
      removed = false;
      for (int i = 0; i < mesh_.n_faces(); ++i) {
        VertexId opposite;
        if (in_[FaceId(i)] && count_ > 1 && shared(FaceId(i), &opposite) == 1) {
          remove(FaceId(i));
          removed = true;
        }
      }
    }
  }

  /// Removes a patch face with one boundary edge and an interior opposite corner, creating no ear: one more
  /// boundary vertex.
  void remove_boundary_face() {
    for (int i = 0; i < mesh_.n_faces(); ++i) {
      const FaceId f(i);
      VertexId opposite;
      if (!in_[f] || shared(f, &opposite) != 2) continue;
      // The corner opposite the boundary edge must be interior.
      VertexId corner;
      for (HalfedgeId h : mesh_.face_halfedges(f)) {
        const FaceId g = mesh_.face(Mesh::twin(h));
        if (!g.valid() || !in_[g]) corner = mesh_.tail(mesh_.prev(h));
      }
      if (on_boundary(corner)) continue;
      remove(f);
      bool ear = false;
      for (HalfedgeId h : mesh_.face_halfedges(f)) {
        const FaceId g = mesh_.face(Mesh::twin(h));
        ear = ear || (g.valid() && in_[g] && shared(g, &opposite) <= 1);
      }
      if (!ear) return;
      add(f);
    }
    throw std::runtime_error("remove_boundary_face: no face to remove");
  }

  [[nodiscard]] int boundary_count() const { return boundary_edges_; }

  [[nodiscard]] TriangleMesh extract() const {
    std::vector<int> index(static_cast<size_t>(mesh_.n_vertices()), -1);
    TriangleMesh out;
    out.F.resize(count_, 3);
    std::vector<int> order;
    int f_out = 0;
    for (int i = 0; i < mesh_.n_faces(); ++i) {
      if (!in_[FaceId(i)]) continue;
      for (int c = 0; c < 3; ++c) {
        int& k = index[static_cast<size_t>(whole_.F(i, c))];
        if (k < 0) {
          k = static_cast<int>(order.size());
          order.push_back(whole_.F(i, c));
        }
        out.F(f_out, c) = k;
      }
      ++f_out;
    }
    out.V.resize(static_cast<Eigen::Index>(order.size()), 3);
    for (size_t k = 0; k < order.size(); ++k) out.V.row(static_cast<Eigen::Index>(k)) = whole_.V.row(order[k]);
    return out;
  }

 private:
  int shared(FaceId f, VertexId* opposite) const {
    int s = 0;
    for (HalfedgeId h : mesh_.face_halfedges(f)) {
      const FaceId g = mesh_.face(Mesh::twin(h));
      if (g.valid() && in_[g]) {
        ++s;
        *opposite = mesh_.tail(mesh_.prev(h));
      }
    }
    return s;
  }

  bool can_add(FaceId f) const {
    if (in_[f]) return false;
    VertexId opposite;
    const int s = shared(f, &opposite);
    return (s == 1 && uses_[opposite] == 0) || s == 2;
  }

  bool on_boundary(VertexId v) const {
    bool b = false;
    mesh_.for_each_outgoing(v, [&](HalfedgeId h) {
      const FaceId l = mesh_.face(h);
      const FaceId r = mesh_.face(Mesh::twin(h));
      b = b || ((l.valid() && in_[l]) != (r.valid() && in_[r]));
    });
    return b;
  }

  void remove(FaceId f) {
    VertexId opposite;
    boundary_edges_ -= 3 - 2 * shared(f, &opposite);
    in_[f] = 0;
    for (VertexId v : mesh_.face_vertices(f)) --uses_[v];
    --count_;
  }

  void add(FaceId f) {
    VertexId opposite;
    boundary_edges_ += 3 - 2 * shared(f, &opposite);
    in_[f] = 1;
    for (VertexId v : mesh_.face_vertices(f)) ++uses_[v];
    ++count_;
  }

  const TriangleMesh& whole_;
  Mesh mesh_;
  FaceData<char> in_;
  VertexData<int> uses_;
  int count_ = 0;
  int boundary_edges_ = 0;
};

Eigen::MatrixXd flatten_on_ellipse(const TriangleMesh& d, const Eigen::Vector2d& radii, std::vector<VertexId>& loop) {
  const Mesh mesh(d.F, static_cast<int>(d.V.rows()));
  loop = ccw_boundary_loop(mesh);
  const int n = static_cast<int>(loop.size());
  Eigen::MatrixXd B(n, 2);
  for (int k = 0; k < n; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / n;
    B.row(k) << radii.x() * std::cos(angle), radii.y() * std::sin(angle);
  }
  Eigen::MatrixXd X = tutte_embedding(mesh, d.V, loop, B);
  for (int k = 0; k < n; ++k) X.row(loop[static_cast<size_t>(k)].idx) = B.row(k);
  return X;
}

}  // namespace

FlatDisk grid_disk(int nx, int ny, bool slash) {
  FlatDisk d;
  d.V.resize((nx + 1) * (ny + 1), 3);
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) d.V.row(j * (nx + 1) + i) << i, j, 0;
  }
  d.F = grid_faces(nx, ny, false, slash);
  d.X = d.V.leftCols(2);
  d.P = d.X;
  return d;
}

Eigen::MatrixXi match_boundaries(const FlatDisk& a, const FlatDisk& b) {
  const Mesh ma(a.F, static_cast<int>(a.X.rows()));
  const Mesh mb(b.F, static_cast<int>(b.X.rows()));
  std::map<std::pair<double, double>, int> at;
  for (int i = 0; i < mb.n_vertices(); ++i) {
    if (mb.is_boundary(VertexId(i))) at[{b.X(i, 0), b.X(i, 1)}] = i;
  }
  std::vector<std::pair<int, int>> rows;
  for (int i = 0; i < ma.n_vertices(); ++i) {
    if (!ma.is_boundary(VertexId(i))) continue;
    const auto it = at.find({a.X(i, 0), a.X(i, 1)});
    if (it == at.end()) throw std::runtime_error("match_boundaries: boundary vertex without partner");
    rows.emplace_back(i, it->second);
  }
  Eigen::MatrixXi nu(static_cast<Eigen::Index>(rows.size()), 2);
  for (size_t k = 0; k < rows.size(); ++k) nu.row(static_cast<Eigen::Index>(k)) << rows[k].first, rows[k].second;
  return nu;
}

FlatDisk spiral_strip(int nr, int nt, double turns, double jitter) {
  const double total = turns * 2.0 * std::numbers::pi;
  FlatDisk d;
  d.P.resize(nr * nt, 2);
  for (int j = 0; j < nt; ++j) {
    for (int i = 0; i < nr; ++i) {
      double r = 1.0 + static_cast<double>(i) / (nr - 1);
      double theta = total * static_cast<double>(j) / (nt - 1);
      if (jitter > 0 && i > 0 && i < nr - 1 && j > 0 && j < nt - 1) {
        r += jitter * hash_unit(i, j) / (nr - 1);
        theta += jitter * hash_unit(j + 1000, i) * total / (nt - 1);
      }
      d.P.row(j * nr + i) << r, theta;
    }
  }
  // Parameter (r, theta) is the grid's (x, y): vertex (i, j) has index j * nr + i.
  d.F = grid_faces(nr - 1, nt - 1, jitter > 0, true);
  d.X.resize(nr * nt, 2);
  d.V.resize(nr * nt, 3);
  for (int k = 0; k < nr * nt; ++k) {
    const double r = d.P(k, 0);
    const double theta = d.P(k, 1);
    d.X.row(k) << r * std::cos(theta), r * std::sin(theta);
    d.V.row(k) << d.X(k, 0), d.X(k, 1), 0.3 * theta;
  }
  return d;
}

TriangleMesh subdivide(const TriangleMesh& mesh) {
  const Mesh m(mesh.F, static_cast<int>(mesh.V.rows()));
  const Eigen::Index nv = mesh.V.rows();
  TriangleMesh out;
  out.V.resize(nv + m.n_edges(), 3);
  out.V.topRows(nv) = mesh.V;
  for (int e = 0; e < m.n_edges(); ++e) {
    const HalfedgeId h = Mesh::halfedge(EdgeId(e));
    out.V.row(nv + e) = 0.5 * (mesh.V.row(m.tail(h).idx) + mesh.V.row(m.head(h).idx));
  }
  out.F.resize(4 * mesh.F.rows(), 3);
  for (int f = 0; f < m.n_faces(); ++f) {
    const auto fh = m.face_halfedges(FaceId(f));
    const auto fv = m.face_vertices(FaceId(f));
    std::array<int, 3> mid{};
    for (size_t k = 0; k < 3; ++k) mid[k] = static_cast<int>(nv) + Mesh::edge(fh[k]).idx;  // on edge k -> k+1
    out.F.row(4 * f) << fv[0].idx, mid[0], mid[2];
    out.F.row(4 * f + 1) << fv[1].idx, mid[1], mid[0];
    out.F.row(4 * f + 2) << fv[2].idx, mid[2], mid[1];
    out.F.row(4 * f + 3) << mid[0], mid[1], mid[2];
  }
  return out;
}

FlatPair tutte_pair(const TriangleMesh& a, const TriangleMesh& b, const Eigen::Vector2d& radii) {
  FlatPair pair;
  std::vector<VertexId> loop_a;
  std::vector<VertexId> loop_b;
  pair.m = {a.V, a.F, flatten_on_ellipse(a, radii, loop_a), {}};
  pair.n = {b.V, b.F, flatten_on_ellipse(b, radii, loop_b), {}};
  if (loop_a.size() != loop_b.size()) throw std::runtime_error("tutte_pair: boundary counts differ");
  pair.nu.resize(static_cast<Eigen::Index>(loop_a.size()), 2);
  for (size_t k = 0; k < loop_a.size(); ++k) pair.nu.row(static_cast<Eigen::Index>(k)) << loop_a[k].idx, loop_b[k].idx;
  return pair;
}

FlatPair tutte_pair_of_patches(const TriangleMesh& a, const TriangleMesh& b, int n_faces,
                               const Eigen::Vector2d& radii) {
  // Of a few seeds spread over the mesh, the one whose patch has the shortest boundary (roundest patch).
  auto best_patch = [&](const TriangleMesh& whole) {
    std::unique_ptr<PatchGrower> best;
    for (int k = 0; k < 4; ++k) {
      auto grower = std::make_unique<PatchGrower>(whole);
      grower->grow(static_cast<int>(k * (whole.F.rows() / 4)), n_faces);
      grower->fill_notches();
      grower->trim_ears();
      if (!best || grower->boundary_count() < best->boundary_count()) best = std::move(grower);
    }
    return best;
  };
  const auto ga = best_patch(a);
  const auto gb = best_patch(b);
  while (ga->boundary_count() < gb->boundary_count()) ga->remove_boundary_face();
  while (gb->boundary_count() < ga->boundary_count()) gb->remove_boundary_face();
  return tutte_pair(ga->extract(), gb->extract(), radii);
}

void exp_warp(FlatPair& pair, double lambda) {
  for (Eigen::MatrixXd* X : {&pair.m.X, &pair.n.X}) {
    for (Eigen::Index i = 0; i < X->rows(); ++i) {
      const double r = std::exp(lambda * (*X)(i, 0));
      const double a = lambda * (*X)(i, 1);
      X->row(i) << r * std::cos(a), r * std::sin(a);
    }
  }
}

PointLocator::PointLocator(const Mesh& mesh, const Eigen::MatrixXd& X) : mesh_(mesh), X_(X) {
  lo_ = X.colwise().minCoeff().transpose();
  const Eigen::Vector2d hi = X.colwise().maxCoeff().transpose();
  const int n = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(mesh.n_faces()))));
  nx_ = ny_ = n;
  cell_ = ((hi - lo_) / n).cwiseMax(1e-300);
  buckets_.resize(static_cast<size_t>(nx_ * ny_));
  auto cell_of = [&](double v, double lo, double c, int n_cells) {
    return std::clamp(static_cast<int>(std::floor((v - lo) / c)), 0, n_cells - 1);
  };
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto fv = mesh.face_vertices(FaceId(f));
    Eigen::Vector2d a = X.row(fv[0].idx).transpose();
    Eigen::Vector2d b = a;
    for (VertexId v : fv) {
      a = a.cwiseMin(X.row(v.idx).transpose());
      b = b.cwiseMax(X.row(v.idx).transpose());
    }
    // One cell of slack on each side keeps points on cell borders safe from rounding.
    const int i0 = std::max(0, cell_of(a.x(), lo_.x(), cell_.x(), nx_) - 1);
    const int i1 = std::min(nx_ - 1, cell_of(b.x(), lo_.x(), cell_.x(), nx_) + 1);
    const int j0 = std::max(0, cell_of(a.y(), lo_.y(), cell_.y(), ny_) - 1);
    const int j1 = std::min(ny_ - 1, cell_of(b.y(), lo_.y(), cell_.y(), ny_) + 1);
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) buckets_[static_cast<size_t>(j * nx_ + i)].push_back(f);
    }
  }
}

std::vector<SurfacePoint> PointLocator::locate(const Eigen::Vector2d& z) const {
  const int i = std::clamp(static_cast<int>(std::floor((z.x() - lo_.x()) / cell_.x())), 0, nx_ - 1);
  const int j = std::clamp(static_cast<int>(std::floor((z.y() - lo_.y()) / cell_.y())), 0, ny_ - 1);
  std::vector<SurfacePoint> out;
  for (int f : buckets_[static_cast<size_t>(j * nx_ + i)]) {
    const auto fh = mesh_.face_halfedges(FaceId(f));
    const Eigen::Vector2d p0 = X_.row(mesh_.tail(fh[0]).idx).transpose();
    const Eigen::Vector2d p1 = X_.row(mesh_.tail(fh[1]).idx).transpose();
    const Eigen::Vector2d p2 = X_.row(mesh_.tail(fh[2]).idx).transpose();
    if (orient2d(p0, p1, p2) <= 0) continue;
    const TriangleLocation loc = locate_in_triangle(p0, p1, p2, z);
    SurfacePoint p;
    switch (loc.kind) {
      case TriangleLocation::Kind::kOutside:
        continue;
      case TriangleLocation::Kind::kInside:
        p = SurfacePoint::in_face(FaceId(f), {0, 0, 0});
        break;
      case TriangleLocation::Kind::kOnEdge:
        p = SurfacePoint::on_edge(Mesh::edge(fh[static_cast<size_t>(loc.index)]), 0);
        break;
      case TriangleLocation::Kind::kAtVertex:
        p = SurfacePoint::at_vertex(mesh_.tail(fh[static_cast<size_t>(loc.index)]));
        break;
    }
    if (std::none_of(out.begin(), out.end(), [&](const SurfacePoint& q) { return same_element(p, q); })) {
      out.push_back(p);
    }
  }
  return out;
}

bool same_element(const SurfacePoint& p, const SurfacePoint& q) {
  if (p.kind != q.kind) return false;
  switch (p.kind) {
    case SurfacePoint::Kind::kVertex:
      return p.vertex == q.vertex;
    case SurfacePoint::Kind::kEdge:
      return p.edge == q.edge;
    case SurfacePoint::Kind::kFace:
      return p.face == q.face;
  }
  return false;
}

}  // namespace liftmap::testing
