#include "lift/disk_overlay.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <unordered_set>

#include "core/errors.h"
#include "lift/exact_predicates.h"

namespace liftmap {

namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Point = Kernel::Point_2;
using Triangle = Kernel::Triangle_2;

/// The corners of a face in the plane, in the order of face_vertices.
std::array<Eigen::Vector2d, 3> corners(const Mesh& mesh, const Eigen::MatrixXd& X, FaceId f) {
  const auto v = mesh.face_vertices(f);
  return {X.row(v[0].idx).transpose(), X.row(v[1].idx).transpose(), X.row(v[2].idx).transpose()};
}

/// True if some edge line of `a` has all corners of `b` on its closed outer side: the triangles' interiors are
/// disjoint (half of the separating-axis test; both triangles counter-clockwise).
bool separated_by_edge_of(const std::array<Eigen::Vector2d, 3>& a, const std::array<Eigen::Vector2d, 3>& b) {
  for (size_t k = 0; k < 3; ++k) {
    const auto& p = a[k];
    const auto& q = a[(k + 1) % 3];
    if (orient2d(p, q, b[0]) <= 0 && orient2d(p, q, b[1]) <= 0 && orient2d(p, q, b[2]) <= 0) return true;
  }
  return false;
}

/// The interiors of two counter-clockwise triangles meet.
bool interiors_meet(const std::array<Eigen::Vector2d, 3>& a, const std::array<Eigen::Vector2d, 3>& b) {
  return !separated_by_edge_of(a, b) && !separated_by_edge_of(b, a);
}

/// The segment [p, q] meets the interior of the counter-clockwise triangle t.
bool segment_meets_interior(const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                            const std::array<Eigen::Vector2d, 3>& t) {
  for (size_t k = 0; k < 3; ++k) {
    if (orient2d(t[k], t[(k + 1) % 3], p) <= 0 && orient2d(t[k], t[(k + 1) % 3], q) <= 0) return false;
  }
  const int o0 = orient2d(p, q, t[0]), o1 = orient2d(p, q, t[1]), o2 = orient2d(p, q, t[2]);
  return !((o0 >= 0 && o1 >= 0 && o2 >= 0) || (o0 <= 0 && o1 <= 0 && o2 <= 0));
}

/// The faces of `mesh` around the element of p (the face itself, an edge's faces, a vertex's faces).
std::vector<FaceId> faces_around(const Mesh& mesh, const SurfacePoint& p) {
  std::vector<FaceId> out;
  switch (p.kind) {
    case SurfacePoint::Kind::kFace:
      out.push_back(p.face);
      break;
    case SurfacePoint::Kind::kEdge:
      for (const HalfedgeId h : {Mesh::halfedge(p.edge), Mesh::twin(Mesh::halfedge(p.edge))}) {
        if (!mesh.is_boundary(h)) out.push_back(mesh.face(h));
      }
      break;
    case SurfacePoint::Kind::kVertex:
      mesh.for_each_outgoing(p.vertex, [&](HalfedgeId h) {
        if (!mesh.is_boundary(h)) out.push_back(mesh.face(h));
      });
      break;
  }
  return out;
}

/// The faces of N^ over Phi(fm): those around f(corner) overlapping Phi(fm), grown across edges of N^ that meet
/// the interior of Phi(fm).
std::vector<FaceId> faces_over(const LiftedBijection& bijection, const Mesh& M, const Eigen::MatrixXd& Phi,
                               const Mesh& N, const Eigen::MatrixXd& Psi, FaceId fm) {
  const auto tm = corners(M, Phi, fm);
  std::vector<FaceId> found;
  std::unordered_set<int> seen;
  for (const FaceId g : faces_around(N, bijection.f()[M.face_vertices(fm)[0]])) {
    if (interiors_meet(tm, corners(N, Psi, g)) && seen.insert(g.idx).second) found.push_back(g);
  }
  for (size_t i = 0; i < found.size(); ++i) {
    for (const HalfedgeId h : N.face_halfedges(found[i])) {
      const HalfedgeId t = Mesh::twin(h);
      if (N.is_boundary(t) || seen.count(N.face(t).idx)) continue;
      const Eigen::Vector2d p = Psi.row(N.tail(h).idx).transpose(), q = Psi.row(N.head(h).idx).transpose();
      if (segment_meets_interior(p, q, tm) && seen.insert(N.face(t).idx).second) found.push_back(N.face(t));
    }
  }
  return found;
}

/// Where a cell corner lies in a face's closure: the smallest element holding it.
struct Located {
  SurfacePoint::Kind kind = SurfacePoint::Kind::kFace;
  int index = -1;  ///< kVertex: corner; kEdge: edge from corner index to index + 1; kFace: -1

  /// The face's edge lines through the point, as bits 0-2 (edge k runs from corner k to corner k + 1).
  [[nodiscard]] unsigned lines() const {
    if (kind == SurfacePoint::Kind::kEdge) return 1U << index;
    if (kind == SurfacePoint::Kind::kVertex) return (1U << index) | (1U << ((index + 2) % 3));
    return 0;
  }
};

Located located(const TriangleLocation& t) {
  switch (t.kind) {
    case TriangleLocation::Kind::kInside:
      return {SurfacePoint::Kind::kFace, -1};
    case TriangleLocation::Kind::kOnEdge:
      return {SurfacePoint::Kind::kEdge, t.index};
    case TriangleLocation::Kind::kAtVertex:
      return {SurfacePoint::Kind::kVertex, t.index};
    case TriangleLocation::Kind::kOutside:
      break;
  }
  return {};
}

/// A corner of a cell: where it lies in the face of M^ and in the face of N^, and its coordinates there.
struct Corner {
  Located m, n;
  std::array<double, 3> wm{}, wn{};  ///< barycentric coordinates in the two faces
  Eigen::Vector2d x;                 ///< position in the plane (rounded)

  /// The six edge lines of the two faces through the corner (bits 0-2: M^'s face, 3-5: N^'s face).
  [[nodiscard]] unsigned lines() const { return m.lines() | (n.lines() << 3U); }
};

double cross2(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

/// Barycentric coordinates of x in the triangle t from sub-areas in extended precision, clamped: the flattened
/// triangles can be far smaller than their surface triangles, which magnifies any rounding here.
std::array<double, 3> barycentric(const std::array<Eigen::Vector2d, 3>& t, const Eigen::Vector2d& x) {
  std::array<long double, 3> w{};
  long double sum = 0;
  for (size_t k = 0; k < 3; ++k) {
    const Eigen::Vector2d& p = t[(k + 1) % 3];
    const Eigen::Vector2d& q = t[(k + 2) % 3];
    const long double a = (static_cast<long double>(p.x()) - x.x()) * (static_cast<long double>(q.y()) - x.y()) -
                          (static_cast<long double>(p.y()) - x.y()) * (static_cast<long double>(q.x()) - x.x());
    w[k] = std::max(0.0L, a);
    sum += w[k];
  }
  if (sum <= 0) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
  return clamp_barycentric(
      {static_cast<double>(w[0] / sum), static_cast<double>(w[1] / sum), static_cast<double>(w[2] / sum)});
}

/// Barycentric coordinates of a point at `loc` in a triangle: exact at a corner; on an edge from the parameter s
/// along it (from corner index toward index + 1); inside from the position.
std::array<double, 3> weights(const Located& loc, double s, const std::array<Eigen::Vector2d, 3>& t,
                              const Eigen::Vector2d& x) {
  std::array<double, 3> w{0, 0, 0};
  const auto k = static_cast<size_t>(loc.index);
  if (loc.kind == SurfacePoint::Kind::kVertex) {
    w[k] = 1.0;
  } else if (loc.kind == SurfacePoint::Kind::kEdge) {
    w[k] = 1.0 - s;
    w[(k + 1) % 3] = s;
  } else {
    w = barycentric(t, x);
  }
  return w;
}

/// Parameter of x along the edge from corner k of t to corner k + 1 (projection, clamped to [0, 1]).
double edge_parameter(const std::array<Eigen::Vector2d, 3>& t, int k, const Eigen::Vector2d& x) {
  using L = long double;
  const Eigen::Vector2d& p = t[static_cast<size_t>(k)];
  const Eigen::Vector2d& q = t[static_cast<size_t>((k + 1) % 3)];
  const L dx = L(q.x()) - p.x(), dy = L(q.y()) - p.y();
  const L s = ((L(x.x()) - p.x()) * dx + (L(x.y()) - p.y()) * dy) / (dx * dx + dy * dy);
  return std::clamp(static_cast<double>(s), 0.0, 1.0);
}

/// Where the segments p -> q and u -> v cross (known to cross properly): the parameters along each, in extended
/// precision.
std::pair<double, double> crossing_parameters(const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                                              const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
  using L = long double;
  const L dx = L(q.x()) - p.x(), dy = L(q.y()) - p.y();  // q - p
  const L ex = L(v.x()) - u.x(), ey = L(v.y()) - u.y();  // v - u
  const L fx = L(u.x()) - p.x(), fy = L(u.y()) - p.y();  // u - p
  const L den = dx * ey - dy * ex;
  const auto t = static_cast<double>((fx * ey - fy * ex) / den);
  const auto s = static_cast<double>((fx * dy - fy * dx) / den);
  return {std::clamp(t, 0.0, 1.0), std::clamp(s, 0.0, 1.0)};
}

/// The corners of the cell a ∩ b from exact predicates on the input coordinates: corners of either triangle in
/// the other, and proper crossings of their edges. Unordered; a corner shared by both triangles appears once.
std::vector<Corner> cell_corners(const std::array<Eigen::Vector2d, 3>& a, const std::array<Eigen::Vector2d, 3>& b) {
  std::vector<Corner> out;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d& x = a[static_cast<size_t>(k)];
    const Located n = located(locate_in_triangle(b[0], b[1], b[2], x));
    if (locate_in_triangle(b[0], b[1], b[2], x).kind == TriangleLocation::Kind::kOutside) continue;
    const Located m{SurfacePoint::Kind::kVertex, k};
    const double s = n.kind == SurfacePoint::Kind::kEdge ? edge_parameter(b, n.index, x) : 0.0;
    out.push_back({m, n, weights(m, 0, a, x), weights(n, s, b, x), x});
  }
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d& x = b[static_cast<size_t>(k)];
    const TriangleLocation loc = locate_in_triangle(a[0], a[1], a[2], x);
    if (loc.kind == TriangleLocation::Kind::kOutside || loc.kind == TriangleLocation::Kind::kAtVertex) continue;
    const Located m = located(loc);
    const Located n{SurfacePoint::Kind::kVertex, k};
    const double s = m.kind == SurfacePoint::Kind::kEdge ? edge_parameter(a, m.index, x) : 0.0;
    out.push_back({m, n, weights(m, s, a, x), weights(n, 0, b, x), x});
  }
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d& p = a[static_cast<size_t>(i)];
    const Eigen::Vector2d& q = a[static_cast<size_t>((i + 1) % 3)];
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector2d& u = b[static_cast<size_t>(j)];
      const Eigen::Vector2d& v = b[static_cast<size_t>((j + 1) % 3)];
      if (orient2d(p, q, u) * orient2d(p, q, v) >= 0 || orient2d(u, v, p) * orient2d(u, v, q) >= 0) continue;
      const auto [t, s] = crossing_parameters(p, q, u, v);
      const Located m{SurfacePoint::Kind::kEdge, i};
      const Located n{SurfacePoint::Kind::kEdge, j};
      const Eigen::Vector2d x = p + t * (q - p);
      out.push_back({m, n, weights(m, t, a, x), weights(n, s, b, x), x});
    }
  }
  return out;
}

/// Orders the corners of a convex cell counter-clockwise by angle around their mean. Returns false if the order
/// is not certain: two corners nearly in the same direction, or neighbours that share no edge line (every side
/// of the cell lies on an edge of one of the two faces).
bool order_corners(std::vector<Corner>& corners) {
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (const Corner& k : corners) c += k.x;
  c /= static_cast<double>(corners.size());
  double scale = 0;
  for (const Corner& k : corners) scale = std::max(scale, (k.x - c).norm());
  std::vector<std::pair<double, size_t>> angle;
  for (size_t i = 0; i < corners.size(); ++i) {
    const Eigen::Vector2d d = corners[i].x - c;
    if (d.norm() < 1e-6 * scale) return false;
    angle.emplace_back(std::atan2(d.y(), d.x()), i);
  }
  std::sort(angle.begin(), angle.end());
  std::vector<Corner> sorted;
  for (size_t i = 0; i < angle.size(); ++i) {
    const double gap =
        i + 1 < angle.size() ? angle[i + 1].first - angle[i].first : angle[0].first + 2 * M_PI - angle[i].first;
    if (gap < 1e-6) return false;
    sorted.push_back(corners[angle[i].second]);
  }
  for (size_t i = 0; i < sorted.size(); ++i) {
    if ((sorted[i].lines() & sorted[(i + 1) % sorted.size()].lines()) == 0) return false;
  }
  corners = std::move(sorted);
  return true;
}

Point to_point(const Eigen::Vector2d& p) { return {p.x(), p.y()}; }

/// Where an exact point lies in the closure of the triangle t.
Located exact_locate(const std::array<Point, 3>& t, const Point& p) {
  std::array<bool, 3> on{};
  for (size_t k = 0; k < 3; ++k) on[k] = CGAL::orientation(t[k], t[(k + 1) % 3], p) == CGAL::COLLINEAR;
  const int n = on[0] + on[1] + on[2];
  if (n == 0) return {SurfacePoint::Kind::kFace, -1};
  if (n == 1) return {SurfacePoint::Kind::kEdge, on[0] ? 0 : (on[1] ? 1 : 2)};
  for (int k = 0; k < 3; ++k) {  // edges k - 1 and k share corner k
    if (on[static_cast<size_t>(k)] && on[static_cast<size_t>((k + 2) % 3)]) return {SurfacePoint::Kind::kVertex, k};
  }
  return {};
}

/// The double nearest an exact number. CGAL::to_double of a lazy exact number rounds its interval approximation,
/// which it trusts to a relative precision of only 1e-5 (triceratops to man with 10 random landmarks: a corner's two
/// copies were 1.2e-10 apart in the plane and 4.7e-11 of the mesh apart on the disks, and the map failed its overlay
/// check); the exact value is rounded once here.
double rounded(const Kernel::FT& x) { return CGAL::to_double(x.exact()); }

/// Barycentric coordinates of an exact point from exact sub-areas, each rounded once.
std::array<double, 3> exact_weights(const std::array<Point, 3>& t, const Point& p) {
  const Kernel::FT total = CGAL::area(t[0], t[1], t[2]);
  std::array<double, 3> w{};
  for (size_t k = 0; k < 3; ++k) w[k] = rounded(CGAL::area(p, t[(k + 1) % 3], t[(k + 2) % 3]) / total);
  return w;
}

/// Weights of a point at `loc`: zero off its element, exactly 1 at a corner, summing to 1.
std::array<double, 3> snap(const Located& loc, std::array<double, 3> w) {
  if (loc.kind == SurfacePoint::Kind::kVertex) {
    w = {0, 0, 0};
    w[static_cast<size_t>(loc.index)] = 1.0;
  } else if (loc.kind == SurfacePoint::Kind::kEdge) {
    w[static_cast<size_t>((loc.index + 2) % 3)] = 0.0;
  }
  return clamp_barycentric(w);
}

/// The cell a ∩ b with exact constructions (CGAL), for cells whose corners are too close to order in floating
/// point: counter-clockwise, without repeats; empty if the cell has no area.
std::vector<Corner> exact_cell(const std::array<Eigen::Vector2d, 3>& a, const std::array<Eigen::Vector2d, 3>& b) {
  const std::array<Point, 3> ea{to_point(a[0]), to_point(a[1]), to_point(a[2])};
  const std::array<Point, 3> eb{to_point(b[0]), to_point(b[1]), to_point(b[2])};
  const auto result = CGAL::intersection(Triangle(ea[0], ea[1], ea[2]), Triangle(eb[0], eb[1], eb[2]));
  std::vector<Point> poly;
  if (!result) return {};
  if (const auto* t = boost::get<Triangle>(&*result)) {
    poly = {t->vertex(0), t->vertex(1), t->vertex(2)};
  } else if (const auto* v = boost::get<std::vector<Point>>(&*result)) {
    poly = *v;
  } else {
    return {};
  }
  poly.erase(std::unique(poly.begin(), poly.end()), poly.end());
  while (poly.size() > 1 && poly.front() == poly.back()) poly.pop_back();
  if (poly.size() < 3) return {};
  Kernel::FT area2 = 0;
  for (size_t i = 1; i + 1 < poly.size(); ++i) area2 += CGAL::area(poly[0], poly[i], poly[i + 1]);
  if (CGAL::is_zero(area2)) return {};
  if (CGAL::is_negative(area2)) std::reverse(poly.begin(), poly.end());
  std::vector<Corner> out;
  out.reserve(poly.size());
  for (const Point& p : poly)
    out.push_back({exact_locate(ea, p),
                   exact_locate(eb, p),
                   exact_weights(ea, p),
                   exact_weights(eb, p),
                   {rounded(p.x()), rounded(p.y())}});
  for (Corner& k : out) {
    // Exact coordinates on an edge or at a corner keep their zeros.
    k.wm = snap(k.m, k.wm);
    k.wn = snap(k.n, k.wn);
  }
  return out;
}

/// The SurfacePoint of a corner in face f of `mesh`: the smallest element holding it.
SurfacePoint surface_point(const Mesh& mesh, FaceId f, const Located& at, const std::array<double, 3>& w) {
  const auto fh = mesh.face_halfedges(f);
  switch (at.kind) {
    case SurfacePoint::Kind::kVertex:
      return SurfacePoint::at_vertex(mesh.tail(fh[static_cast<size_t>(at.index)]));
    case SurfacePoint::Kind::kEdge: {
      const auto k = static_cast<size_t>(at.index);
      const double s = w[(k + 1) % 3] / (w[k] + w[(k + 1) % 3]);  // from corner k toward corner k + 1
      const EdgeId e = Mesh::edge(fh[k]);
      return SurfacePoint::on_edge(e, fh[k] == Mesh::halfedge(e) ? s : 1.0 - s);
    }
    case SurfacePoint::Kind::kFace:
      return SurfacePoint::in_face(f, w);
  }
  return {};
}

/// An element of a mesh as a key {kind, index}: equal keys on both sides make one overlay vertex.
std::array<int, 2> element_key(const Mesh& mesh, FaceId f, const Located& at) {
  const auto fh = mesh.face_halfedges(f);
  switch (at.kind) {
    case SurfacePoint::Kind::kVertex:
      return {0, mesh.tail(fh[static_cast<size_t>(at.index)]).idx};
    case SurfacePoint::Kind::kEdge:
      return {1, Mesh::edge(fh[static_cast<size_t>(at.index)]).idx};
    case SurfacePoint::Kind::kFace:
      return {2, f.idx};
  }
  return {-1, -1};
}

/// The cells of one face of M^, each as its counter-clockwise corners and the face of N^.
struct FaceCells {
  std::vector<std::vector<Corner>> cells;
  std::vector<FaceId> faces_n;
  int exact = 0;  ///< cells that needed exact constructions
};

/// Intersects face fm of M^ with the faces of N^ over it.
FaceCells cells_of_face(const LiftedBijection& bijection, const Mesh& M, const Eigen::MatrixXd& Phi, const Mesh& N,
                        const Eigen::MatrixXd& Psi, FaceId fm) {
  FaceCells out;
  const auto a = corners(M, Phi, fm);
  for (const FaceId fn : faces_over(bijection, M, Phi, N, Psi, fm)) {
    const auto b = corners(N, Psi, fn);
    std::vector<Corner> cell = cell_corners(a, b);
    if (cell.size() < 3) continue;
    if (!order_corners(cell)) {
      cell = exact_cell(a, b);
      ++out.exact;
      if (cell.size() < 3) continue;
    }
    out.cells.push_back(std::move(cell));
    out.faces_n.push_back(fn);
  }
  return out;
}

/// Builds the overlay from cells; equal (element of M^, element of N^) pairs are one vertex.
class OverlayBuilder {
 public:
  OverlayBuilder(const Mesh& M, const Mesh& N) : M_(M), N_(N) {}

  /// Adds a cell of faces fm and fn (corners counter-clockwise) as triangles.
  void add_cell(FaceId fm, FaceId fn, const std::vector<Corner>& cell) {
    std::vector<int> ids;
    ids.reserve(cell.size());
    for (const Corner& k : cell) ids.push_back(vertex(fm, fn, k));
    const size_t n = cell.size();
    for (size_t apex = 0; apex < n; ++apex) {
      // A fan triangle is flat exactly when its three corners share an edge line of one of the faces.
      bool proper = true;
      for (size_t i = 1; i + 1 < n && proper; ++i) {
        proper = (cell[apex].lines() & cell[(apex + i) % n].lines() & cell[(apex + i + 1) % n].lines()) == 0;
      }
      if (!proper) continue;
      for (size_t i = 1; i + 1 < n; ++i) emit(ids[apex], ids[(apex + i) % n], ids[(apex + i + 1) % n], fm, fn);
      return;
    }
    Corner centre{{}, {}, {0, 0, 0}, {0, 0, 0}, Eigen::Vector2d::Zero()};
    for (const Corner& k : cell) {
      for (size_t j = 0; j < 3; ++j) {
        centre.wm[j] += k.wm[j] / static_cast<double>(n);
        centre.wn[j] += k.wn[j] / static_cast<double>(n);
      }
      centre.x += k.x / static_cast<double>(n);
    }
    const int c = vertex(fm, fn, centre);
    for (size_t i = 0; i < n; ++i) emit(c, ids[i], ids[(i + 1) % n], fm, fn);
  }

  DiskOverlay take() { return std::move(out_); }

 private:
  int vertex(FaceId fm, FaceId fn, const Corner& k) {
    const auto km = element_key(M_, fm, k.m), kn = element_key(N_, fn, k.n);
    const std::array<int, 4> key{km[0], km[1], kn[0], kn[1]};
    const auto [it, fresh] = ids_.emplace(key, static_cast<int>(out_.on_m.size()));
    if (fresh) {
      out_.on_m.push_back(surface_point(M_, fm, k.m, k.wm));
      out_.on_n.push_back(surface_point(N_, fn, k.n, k.wn));
      out_.plane.push_back(k.x);
    }
    return it->second;
  }

  void emit(int i, int j, int k, FaceId fm, FaceId fn) {
    out_.triangles.push_back({i, j, k});
    out_.face_m.push_back(fm.idx);
    out_.face_n.push_back(fn.idx);
  }

  const Mesh& M_;
  const Mesh& N_;
  std::map<std::array<int, 4>, int> ids_;
  DiskOverlay out_;
};

double cell_doubled_area(const std::vector<Corner>& cell) {
  double a = 0;
  for (size_t i = 1; i + 1 < cell.size(); ++i) a += cross2(cell[i].x - cell[0].x, cell[i + 1].x - cell[0].x);
  return a;
}

double doubled_area(const std::array<Eigen::Vector2d, 3>& t) { return cross2(t[1] - t[0], t[2] - t[0]); }

}  // namespace

DiskOverlay overlay_disks(const LiftedBijection& bijection, const Mesh& M, const Eigen::MatrixXd& Phi, const Mesh& N,
                          const Eigen::MatrixXd& Psi) {
  std::vector<FaceCells> cells(static_cast<size_t>(M.n_faces()));
#pragma omp parallel for schedule(dynamic, 256)
  for (int i = 0; i < M.n_faces(); ++i)
    cells[static_cast<size_t>(i)] = cells_of_face(bijection, M, Phi, N, Psi, FaceId(i));
  OverlayBuilder builder(M, N);
  for (int i = 0; i < M.n_faces(); ++i) {
    const FaceCells& fc = cells[static_cast<size_t>(i)];
    double covered = 0;
    for (size_t c = 0; c < fc.cells.size(); ++c) {
      builder.add_cell(FaceId(i), fc.faces_n[c], fc.cells[c]);
      covered += cell_doubled_area(fc.cells[c]);
    }
    const double area = doubled_area(corners(M, Phi, FaceId(i)));
    if (std::abs(covered - area) > 1e-6 * area) {
      throw PipelineError("overlay: face " + std::to_string(i) + " of M^ is covered by cells of doubled area " +
                          figure(covered, 6) + ", not its own " + figure(area, 6) +
                          " (off by more than 1e-6 of it: the two flattenings do not tile the face)");
    }
  }
  return builder.take();
}

}  // namespace liftmap
