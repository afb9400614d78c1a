#include "lift/lift_map.h"

#include <algorithm>
#include <deque>
#include <numeric>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "core/parallel_for_each.h"
#include "lift/exact_predicates.h"
#include "lift/format_point.h"
#include "lift/lift_path.h"

namespace liftmap {

namespace {

using Roots = std::vector<std::pair<VertexId, VertexId>>;

std::string element_name(const SurfacePoint& p) {
  switch (p.kind) {
    case SurfacePoint::Kind::kVertex:
      return "vertex " + std::to_string(p.vertex.idx);
    case SurfacePoint::Kind::kEdge:
      return "edge " + std::to_string(p.edge.idx);
    case SurfacePoint::Kind::kFace:
      return "face " + std::to_string(p.face.idx);
  }
  return "?";
}

/// Index of the element of `p`, whichever kind it is.
int element_index(const SurfacePoint& p) {
  switch (p.kind) {
    case SurfacePoint::Kind::kVertex:
      return p.vertex.idx;
    case SurfacePoint::Kind::kEdge:
      return p.edge.idx;
    case SurfacePoint::Kind::kFace:
      return p.face.idx;
  }
  return -1;
}

bool same_element(const SurfacePoint& p, const SurfacePoint& q) {
  return p.kind == q.kind && element_index(p) == element_index(q);
}

void require_disk(const Mesh& mesh, const std::string& name) {
  for (int i = 0; i < mesh.n_vertices(); ++i) {
    if (mesh.is_isolated(VertexId(i))) {
      throw InvalidInputError("lifting: " + name + " has isolated vertex " + std::to_string(i));
    }
  }
  const auto loops = mesh.boundary_loops();
  if (loops.size() != 1 || mesh.euler_characteristic() != 1) {
    throw InvalidInputError("lifting: " + name + " is not a disk (" + std::to_string(loops.size()) +
                            " boundary loops, Euler characteristic " + std::to_string(mesh.euler_characteristic()) +
                            ")");
  }
}

}  // namespace

/// One direction of the bijection: images of the source vertices on the target, and point evaluation.
class LiftedBijection::OneWay {
 public:
  OneWay(const Mesh& source, const Eigen::MatrixXd& X_source, const Mesh& target, const Eigen::MatrixXd& X_target,
         const Roots& roots, bool verify, const std::string& map_name)
      : source_(source), lifter_(make_lifter(target, X_target, map_name)), name_(map_name) {
    x_.resize(static_cast<size_t>(source.n_vertices()));
    for (int i = 0; i < source.n_vertices(); ++i) x_[static_cast<size_t>(i)] = X_source.row(i).transpose();
    lift_tree(roots, verify);
  }

  [[nodiscard]] const VertexData<SurfacePoint>& images() const { return images_; }

  [[nodiscard]] SurfacePoint evaluate(const SurfacePoint& p) const {
    switch (p.kind) {
      case SurfacePoint::Kind::kVertex:
        return images_[p.vertex];
      case SurfacePoint::Kind::kEdge:
        return evaluate_edge(p.edge, p.t);
      case SurfacePoint::Kind::kFace:
        return evaluate_face(p.face, p.bary);
    }
    return {};
  }

  /// evaluate() at every point; the interior points of one edge share the lift of that edge (lift_edge). The work
  /// runs as parallel_for_each's items: one per edge holding interior points, one per other point.
  [[nodiscard]] std::vector<SurfacePoint> evaluate_all(const std::vector<SurfacePoint>& points) const {
    const auto inside_edge = [&](size_t i) {
      return points[i].kind == SurfacePoint::Kind::kEdge && points[i].t > 0.0 && points[i].t < 1.0;
    };
    // Every point's index: the others first, then the interior edge points by edge (in input order within an edge).
    std::vector<size_t> order(points.size());
    std::iota(order.begin(), order.end(), size_t{0});
    const auto edge_key = [&](size_t i) { return inside_edge(i) ? points[i].edge.idx : -1; };
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return edge_key(a) < edge_key(b); });
    std::vector<size_t> item_start;  // item j evaluates order[item_start[j]] .. order[item_start[j + 1] - 1]
    for (size_t k = 0; k < order.size(); ++k) {
      if (k == 0 || edge_key(order[k]) < 0 || edge_key(order[k]) != edge_key(order[k - 1])) item_start.push_back(k);
    }
    item_start.push_back(order.size());
    std::vector<SurfacePoint> out(points.size());
    const int n_items = static_cast<int>(item_start.size()) - 1;
    parallel_for_each(n_items, n_items, [&](int j) {
      const size_t first = item_start[static_cast<size_t>(j)], last = item_start[static_cast<size_t>(j) + 1];
      if (!inside_edge(order[first])) {
        out[order[first]] = evaluate(points[order[first]]);
        return;
      }
      const EdgeId e = points[order[first]].edge;
      const LiftTrace trace = lift_edge(e);
      for (size_t k = first; k < last; ++k) out[order[k]] = point_on_edge_lift(e, trace, points[order[k]].t);
    });
    return out;
  }

 private:
  static PathLifter make_lifter(const Mesh& target, const Eigen::MatrixXd& X_target, const std::string& map_name) {
    try {
      return PathLifter(target, X_target);
    } catch (const PipelineError& e) {
      throw PipelineError("lifting " + map_name + ": target " + e.what());
    }
  }

  [[nodiscard]] const Eigen::Vector2d& x(VertexId v) const { return x_[static_cast<size_t>(v.idx)]; }

  /// Breadth-first spanning tree from all roots at once; each tree edge is lifted from its known end.
  void lift_tree(const Roots& roots, bool verify) {
    const int nv = source_.n_vertices();
    images_.resize(nv);
    VertexData<char> known(nv, 0);
    EdgeData<char> tree(source_.n_edges(), 0);
    std::deque<VertexId> queue;
    for (const auto& [s, t] : roots) {
      images_[s] = SurfacePoint::at_vertex(t);
      known[s] = 1;
      queue.push_back(s);
    }
    while (!queue.empty()) {
      const VertexId u = queue.front();
      queue.pop_front();
      source_.for_each_outgoing(u, [&](HalfedgeId h) {
        const VertexId w = source_.head(h);
        if (known[w]) return;
        images_[w] = lifter_.lift_segment(images_[u], x(u), x(w));
        known[w] = 1;
        tree[Mesh::edge(h)] = 1;
        queue.push_back(w);
      });
    }
    if (!verify) return;
    for (int i = 0; i < source_.n_edges(); ++i) {
      if (tree[EdgeId(i)]) continue;
      const HalfedgeId h = Mesh::halfedge(EdgeId(i));
      const VertexId u = source_.tail(h);
      const VertexId w = source_.head(h);
      const SurfacePoint r = lifter_.lift_segment(images_[u], x(u), x(w));
      if (!same_element(r, images_[w])) {
        throw PipelineError("lifting " + name_ + ": not liftable, the lift of edge (" + std::to_string(u.idx) + ", " +
                            std::to_string(w.idx) + ") from " + format_point(x(u)) + " to " + format_point(x(w)) +
                            " ends in " + element_name(r) + " but the spanning tree put vertex " +
                            std::to_string(w.idx) + " in " + element_name(images_[w]));
      }
    }
    // Same element and same planar point means same point: the target flattening is injective on an element.
    std::vector<std::tuple<int, int, double, double, int>> keys;
    keys.reserve(static_cast<size_t>(nv));
    for (int i = 0; i < nv; ++i) {
      const SurfacePoint& p = images_[VertexId(i)];
      keys.emplace_back(static_cast<int>(p.kind), element_index(p), x_[static_cast<size_t>(i)].x(),
                        x_[static_cast<size_t>(i)].y(), i);
    }
    std::sort(keys.begin(), keys.end());
    for (size_t i = 1; i < keys.size(); ++i) {
      const auto& [k0, e0, x0, y0, v0] = keys[i - 1];
      const auto& [k1, e1, x1, y1, v1] = keys[i];
      if (k0 == k1 && e0 == e1 && x0 == x1 && y0 == y1) {
        throw PipelineError("lifting " + name_ + ": not injective, vertices " + std::to_string(v0) + " and " +
                            std::to_string(v1) + " both map to " + element_name(images_[VertexId(v0)]) + " at " +
                            format_point(x_[static_cast<size_t>(v0)]));
      }
    }
  }

  /// The lift of edge e's segment x(tail) -> x(head), from the tail's image.
  [[nodiscard]] LiftTrace lift_edge(EdgeId e) const {
    const HalfedgeId h = Mesh::halfedge(e);
    LiftTrace trace;
    lifter_.lift_segment(images_[source_.tail(h)], x(source_.tail(h)), x(source_.head(h)), &trace);
    return trace;
  }

  /// The point at parameter t in (0, 1) of edge e, found on the piece of its lift (lift_edge) whose parameter range
  /// holds t.
  [[nodiscard]] SurfacePoint point_on_edge_lift(EdgeId e, const LiftTrace& trace, double t) const {
    const HalfedgeId h = Mesh::halfedge(e);
    size_t k = 0;
    while (k + 1 < trace.faces.size() && trace.s[k + 1] < t) ++k;
    return lifter_.face_point(trace.faces[k], (1.0 - t) * x(source_.tail(h)) + t * x(source_.head(h)));
  }

  /// The edge's image is the lift of the segment x(tail) -> x(head); the point is found on the piece of that
  /// lifted path whose parameter range holds t.
  [[nodiscard]] SurfacePoint evaluate_edge(EdgeId e, double t) const {
    const HalfedgeId h = Mesh::halfedge(e);
    if (t <= 0.0) return images_[source_.tail(h)];
    if (t >= 1.0) return images_[source_.head(h)];
    return point_on_edge_lift(e, lift_edge(e), t);
  }

  [[nodiscard]] SurfacePoint evaluate_face(FaceId f, std::array<double, 3> bary) const {
    const auto fh = source_.face_halfedges(f);
    const std::array<VertexId, 3> c = {source_.tail(fh[0]), source_.tail(fh[1]), source_.tail(fh[2])};
    for (double& b : bary) b = std::max(0.0, b);
    Eigen::Vector2d z = bary[0] * x(c[0]) + bary[1] * x(c[1]) + bary[2] * x(c[2]);
    // Rounding can put z just outside the triangle x(f); snap x onto the edges z fell across.
    std::array<double, 3> snapped = bary;
    for (size_t k = 0; k < 3; ++k) {
      if (orient2d(x(c[k]), x(c[(k + 1) % 3]), z) < 0) snapped[(k + 2) % 3] = 0.0;
    }
    const int positive = (snapped[0] > 0) + (snapped[1] > 0) + (snapped[2] > 0);
    const size_t largest = static_cast<size_t>(std::max_element(bary.begin(), bary.end()) - bary.begin());
    if (positive <= 1) {
      const size_t k = positive == 0
                           ? largest
                           : static_cast<size_t>(std::max_element(snapped.begin(), snapped.end()) - snapped.begin());
      return images_[c[k]];
    }
    if (positive == 2) {
      // The edge opposite the zero corner k0 runs from corner k0+1 to corner k0+2 (halfedge fh[k0+1]).
      const size_t k0 = snapped[0] == 0 ? 0 : (snapped[1] == 0 ? 1 : 2);
      const size_t i = (k0 + 1) % 3;
      const size_t j = (k0 + 2) % 3;
      const double t_h = snapped[j] / (snapped[i] + snapped[j]);
      const HalfedgeId h = fh[i];
      const EdgeId e = Mesh::edge(h);
      return evaluate_edge(e, h == Mesh::halfedge(e) ? t_h : 1.0 - t_h);
    }
    const VertexId from = c[largest];
    long double zx = 0, zy = 0;
    for (size_t k = 0; k < 3; ++k) {
      zx += static_cast<long double>(bary[k]) * x(c[k]).x();
      zy += static_cast<long double>(bary[k]) * x(c[k]).y();
    }
    return lifter_.refine_coordinates(lifter_.lift_segment(images_[from], x(from), z), zx, zy);
  }

  Mesh source_;
  std::vector<Eigen::Vector2d> x_;
  PathLifter lifter_;
  std::string name_;
  VertexData<SurfacePoint> images_;
};

LiftedBijection::LiftedBijection(const Mesh& M, const Eigen::MatrixXd& Phi, const Mesh& N, const Eigen::MatrixXd& Psi,
                                 const Eigen::MatrixXi& nu, const LiftOptions& options) {
  require_disk(M, "M^");
  require_disk(N, "N^");
  if (Phi.rows() != M.n_vertices() || Phi.cols() != 2 || Psi.rows() != N.n_vertices() || Psi.cols() != 2) {
    throw InvalidInputError("lifting: Phi must be #V(M^) by 2 and Psi #V(N^) by 2");
  }
  if (nu.cols() != 2) throw InvalidInputError("lifting: the boundary correspondence nu must be #B by 2");
  VertexData<VertexId> to_n(M.n_vertices());
  VertexData<VertexId> to_m(N.n_vertices());
  Roots f_roots;
  Roots g_roots;
  for (Eigen::Index i = 0; i < nu.rows(); ++i) {
    const int m = nu(i, 0);
    const int n = nu(i, 1);
    const std::string row =
        "lifting: nu row " + std::to_string(i) + " (" + std::to_string(m) + ", " + std::to_string(n) + ")";
    if (m < 0 || m >= M.n_vertices() || n < 0 || n >= N.n_vertices()) throw InvalidInputError(row + ": out of range");
    const VertexId vm(m);
    const VertexId vn(n);
    if (!M.is_boundary(vm) || !N.is_boundary(vn)) throw InvalidInputError(row + ": not a pair of boundary vertices");
    if (to_n[vm].valid() || to_m[vn].valid()) throw InvalidInputError(row + ": vertex listed twice");
    if (Phi(m, 0) != Psi(n, 0) || Phi(m, 1) != Psi(n, 1)) {
      throw InvalidInputError(row + ": Phi = " + format_point(Phi.row(m).transpose()) +
                              " differs from Psi = " + format_point(Psi.row(n).transpose()) +
                              "; the flattenings must agree exactly on the boundary");
    }
    to_n[vm] = vn;
    to_m[vn] = vm;
    f_roots.emplace_back(vm, vn);
    g_roots.emplace_back(vn, vm);
  }
  const std::vector<HalfedgeId> loop = M.boundary_loops().front();
  const size_t n_loop = N.boundary_loops().front().size();
  if (loop.size() != static_cast<size_t>(nu.rows()) || n_loop != loop.size()) {
    throw InvalidInputError("lifting: nu has " + std::to_string(nu.rows()) + " rows but M^ has " +
                            std::to_string(loop.size()) + " and N^ " + std::to_string(n_loop) + " boundary vertices");
  }
  for (const HalfedgeId h : loop) {
    const VertexId a = to_n[M.tail(h)];
    const VertexId b = to_n[M.head(h)];
    bool found = false;
    N.for_each_outgoing(a, [&](HalfedgeId k) { found = found || (N.head(k) == b && N.is_boundary(k)); });
    if (!found) {
      throw InvalidInputError("lifting: nu does not preserve the boundary order: boundary edge (" +
                              std::to_string(M.tail(h).idx) + ", " + std::to_string(M.head(h).idx) +
                              ") of M^ maps to (" + std::to_string(a.idx) + ", " + std::to_string(b.idx) +
                              "), not a boundary edge of N^ in the same direction");
    }
  }
  f_ = std::make_unique<OneWay>(M, Phi, N, Psi, f_roots, options.verify, "f: M^ -> N^ through Psi");
  g_ = std::make_unique<OneWay>(N, Psi, M, Phi, g_roots, options.verify, "g: N^ -> M^ through Phi");
}

LiftedBijection::~LiftedBijection() = default;
LiftedBijection::LiftedBijection(LiftedBijection&&) noexcept = default;
LiftedBijection& LiftedBijection::operator=(LiftedBijection&&) noexcept = default;

const VertexData<SurfacePoint>& LiftedBijection::f() const { return f_->images(); }
const VertexData<SurfacePoint>& LiftedBijection::g() const { return g_->images(); }
SurfacePoint LiftedBijection::evaluate_f(const SurfacePoint& x) const { return f_->evaluate(x); }
SurfacePoint LiftedBijection::evaluate_g(const SurfacePoint& y) const { return g_->evaluate(y); }
std::vector<SurfacePoint> LiftedBijection::evaluate_f(const std::vector<SurfacePoint>& x) const {
  return f_->evaluate_all(x);
}
std::vector<SurfacePoint> LiftedBijection::evaluate_g(const std::vector<SurfacePoint>& y) const {
  return g_->evaluate_all(y);
}

LiftedVertexMaps lift_bijection(const Mesh& M, const Eigen::MatrixXd& Phi, const Mesh& N, const Eigen::MatrixXd& Psi,
                                const Eigen::MatrixXi& nu, const LiftOptions& options) {
  const LiftedBijection lift(M, Phi, N, Psi, nu, options);
  return {lift.f(), lift.g()};
}

}  // namespace liftmap
