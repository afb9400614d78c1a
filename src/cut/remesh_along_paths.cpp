#include "cut/remesh_along_paths.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <map>
#include <string>
#include <unordered_map>

#include "core/errors.h"
#include "cut/edge_key.h"

namespace liftmap {

namespace {

/// The constrained Delaunay triangulation of kernel K, with an int per vertex and per face.
template <class K>
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<
    K,
    CGAL::Triangulation_data_structure_2<
        CGAL::Triangulation_vertex_base_with_info_2<int, K>,
        CGAL::Constrained_triangulation_face_base_2<K, CGAL::Triangulation_face_base_with_info_2<int, K>>>,
    CGAL::No_constraint_intersection_tag>;

/// A vertex of one input face's triangulation: its refined id, its barycentric coordinates in the face and the
/// sides of the face it lies on (bit k: the side from corner k to corner k + 1).
struct FaceVertex {
  int id;
  std::array<double, 3> bary;
  unsigned sides;
};

/// The input faces whose closure contains a point of the input mesh, sorted.
std::vector<int> faces_containing(const Mesh& input, const SurfacePoint& p) {
  std::vector<int> fs;
  switch (p.kind) {
    case SurfacePoint::Kind::kVertex:
      input.for_each_outgoing(p.vertex, [&](HalfedgeId h) {
        if (!input.is_boundary(h)) fs.push_back(input.face(h).idx);
      });
      break;
    case SurfacePoint::Kind::kEdge:
      for (const HalfedgeId h : {Mesh::halfedge(p.edge), Mesh::twin(Mesh::halfedge(p.edge))}) {
        if (!input.is_boundary(h)) fs.push_back(input.face(h).idx);
      }
      break;
    case SurfacePoint::Kind::kFace:
      fs.push_back(p.face.idx);
      break;
  }
  std::sort(fs.begin(), fs.end());
  return fs;
}

/// The input faces whose closures contain both points, sorted: none, one, or the two faces of a common edge.
std::vector<int> common_faces(const Mesh& input, const SurfacePoint& p, const SurfacePoint& q) {
  const auto fp = faces_containing(input, p), fq = faces_containing(input, q);
  std::vector<int> common;
  std::set_intersection(fp.begin(), fp.end(), fq.begin(), fq.end(), std::back_inserter(common));
  return common;
}

unsigned sides_of(const std::array<double, 3>& b) {
  unsigned s = 0;
  for (unsigned k = 0; k < 3; ++k) {
    if (b[(k + 2) % 3] == 0.0) s |= 1u << k;  // no weight at the opposite corner: on side k
  }
  return s;
}

/// The face's corners laid out isometrically in the plane, counter-clockwise.
std::array<Eigen::Vector2d, 3> layout(const RefinedMesh& r, const std::array<VertexId, 3>& c) {
  const Eigen::Vector3d& p0 = r.positions[static_cast<size_t>(c[0].idx)];
  const Eigen::Vector3d& p1 = r.positions[static_cast<size_t>(c[1].idx)];
  const Eigen::Vector3d& p2 = r.positions[static_cast<size_t>(c[2].idx)];
  const Eigen::Vector3d e1 = p1 - p0, e2 = p2 - p0;
  const double l1 = e1.norm();
  const double x = e1.dot(e2) / l1;
  const double y = e1.cross(e2).norm() / l1;
  return {Eigen::Vector2d(0, 0), Eigen::Vector2d(l1, 0), Eigen::Vector2d(x, y)};
}

/// The constrained Delaunay triangulation of one input face: triangles of refined ids, counter-clockwise. With
/// exact constructions (CGAL::Epeck), the points on a side are constructed exactly on its line; with inexact ones
/// (CGAL::Epick, fast) rounding can put them a little off it.
template <class Kernel>
std::vector<std::array<int, 3>> triangulate_face(const std::array<Eigen::Vector2d, 3>& corners,
                                                 const std::vector<FaceVertex>& vertices,
                                                 const std::vector<std::array<int, 2>>& segments, int face) {
  const auto fail = [&](const std::string& what) {
    return PipelineError("cut: re-triangulating input face " + std::to_string(face) + ": " + what);
  };
  using Cdt = liftmap::Cdt<Kernel>;
  Cdt cdt;
  std::vector<typename Cdt::Vertex_handle> handle(vertices.size());
  std::vector<std::pair<double, size_t>> on_side[3];
  using Point = typename Kernel::Point_2;
  std::array<Point, 3> c;
  for (size_t k = 0; k < 3; ++k) c[k] = Point(corners[k].x(), corners[k].y());
  for (size_t i = 0; i < vertices.size(); ++i) {
    const auto& b = vertices[i].bary;
    Point point;
    const unsigned sides = vertices[i].sides;
    if (sides == 1u || sides == 2u || sides == 4u) {  // on one side only: exactly on its line
      const size_t k = sides == 1u ? 0 : sides == 2u ? 1 : 2;
      point = c[k] + (c[(k + 1) % 3] - c[k]) * b[(k + 1) % 3];
    } else if (sides != 0) {  // a corner
      point = c[b[0] == 1.0 ? 0 : b[1] == 1.0 ? 1 : 2];
    } else {
      const Eigen::Vector2d x = b[0] * corners[0] + b[1] * corners[1] + b[2] * corners[2];
      point = Point(x.x(), x.y());
    }
    const size_t before = cdt.number_of_vertices();
    handle[i] = cdt.insert(point);
    if (cdt.number_of_vertices() == before) throw fail("two vertices at one point");
    handle[i]->info() = static_cast<int>(i);
    for (unsigned k = 0; k < 3; ++k) {
      if ((vertices[i].sides >> k) & 1u) on_side[k].emplace_back(b[(k + 1) % 3], i);
    }
  }
  // The three sides, as chains through the points on them, and the path segments.
  for (auto& side : on_side) {
    std::sort(side.begin(), side.end());
    for (size_t j = 0; j + 1 < side.size(); ++j)
      cdt.insert_constraint(handle[side[j].second], handle[side[j + 1].second]);
  }
  const auto index_of = [&](int id) {
    for (size_t i = 0; i < vertices.size(); ++i) {
      if (vertices[i].id == id) return i;
    }
    throw fail("a path segment ends at a vertex not on the face");
  };
  try {
    for (const auto& s : segments) cdt.insert_constraint(handle[index_of(s[0])], handle[index_of(s[1])]);
  } catch (const typename Cdt::Intersection_of_constraints_exception&) {
    throw fail("two path segments cross");
  }
  // Outside: reachable from the infinite face without crossing a constraint (this includes slivers between a side
  // and side points that rounding put a little inside it).
  for (const auto f : cdt.all_face_handles()) f->info() = 0;
  std::vector<typename Cdt::Face_handle> stack{cdt.infinite_face()};
  cdt.infinite_face()->info() = 1;
  while (!stack.empty()) {
    const typename Cdt::Face_handle f = stack.back();
    stack.pop_back();
    for (int i = 0; i < 3; ++i) {
      const typename Cdt::Face_handle n = f->neighbor(i);
      if (n->info() == 0 && !cdt.is_constrained(typename Cdt::Edge(f, i))) {
        n->info() = 1;
        stack.push_back(n);
      }
    }
  }
  std::vector<std::array<int, 3>> out;
  double area = 0;
  for (const auto f : cdt.finite_face_handles()) {
    if (f->info() != 0) continue;
    std::array<int, 3> t{};
    unsigned common = 7;
    for (int k = 0; k < 3; ++k) {
      const FaceVertex& v = vertices[static_cast<size_t>(f->vertex(k)->info())];
      t[static_cast<size_t>(k)] = v.id;
      common &= v.sides;
    }
    if (common != 0) throw fail("a triangle has its three vertices on one side");
    area += CGAL::to_double(CGAL::area(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point()));
    out.push_back(t);
  }
  const double expected = 0.5 * (corners[1] - corners[0]).x() * (corners[2] - corners[0]).y();
  if (!(std::abs(area - expected) <= 1e-9 * expected)) throw fail("the triangles do not tile the face");
  for (const auto& s : segments) {
    typename Cdt::Face_handle f;
    int i = 0;
    if (!cdt.is_edge(handle[index_of(s[0])], handle[index_of(s[1])], f, i)) throw fail("a path segment is split");
  }
  return out;
}

/// Drops every path vertex inside an input face whose two path neighbours lie on that face and on no other common
/// face (as vertices of intermediate refinements leave them), unless the path would be left with one edge: the path
/// then runs straight across each input face, from where it enters to where it leaves, as a geodesic does. Two paths
/// that did not cross do not cross after it: their chords of one face end at points that do not interleave along the
/// face's boundary. \return the number of vertices dropped
int straighten_within_faces(const RefinedMesh& refined, const Mesh& input, std::vector<std::vector<int>>& paths) {
  int dropped = 0;
  for (auto& p : paths) {
    std::vector<int> out;
    for (size_t i = 0; i < p.size(); ++i) {
      const SurfacePoint& x = refined.on_input[static_cast<size_t>(p[i])];
      // A path keeps two edges at least: cutting along a single edge would leave no disk (its two copies would be
      // the whole boundary); two landmarks inside one input face would otherwise be joined straight.
      const bool keeps_two_edges = out.size() + (p.size() - i - 1) >= 3;
      if (i > 0 && i + 1 < p.size() && x.kind == SurfacePoint::Kind::kFace && keeps_two_edges) {
        const auto common = common_faces(input, refined.on_input[static_cast<size_t>(out.back())],
                                         refined.on_input[static_cast<size_t>(p[i + 1])]);
        // Only across the face: neighbours on one common edge would make the chord run along it, possibly over
        // other vertices there.
        if (common.size() == 1 && common[0] == x.face.idx) {
          ++dropped;
          continue;
        }
      }
      out.push_back(p[i]);
    }
    p = std::move(out);
  }
  return dropped;
}

/// The cyclic order of the paths around each vertex where two or more of them meet (their ends: paths touch only
/// there), as path indices counter-clockwise from the smallest: vertex -> order.
std::map<int, std::vector<int>> path_rotations(const Mesh& mesh, const std::vector<std::vector<int>>& paths) {
  std::unordered_map<std::uint64_t, int> path_of_edge;
  std::map<int, int> ends;  // vertex -> number of paths ending there
  for (size_t e = 0; e < paths.size(); ++e) {
    const auto& p = paths[e];
    for (size_t i = 0; i + 1 < p.size(); ++i) path_of_edge[edge_key(p[i], p[i + 1])] = static_cast<int>(e);
    if (p.empty()) continue;
    ++ends[p.front()];
    ++ends[p.back()];
  }
  std::map<int, std::vector<int>> rotations;
  for (const auto& [end, count] : ends) {
    if (count < 2) continue;
    const int v = end;  // a copy: clang 14 (clang-tidy) cannot capture a structured binding in a lambda
    std::vector<int>& order = rotations[v];
    mesh.for_each_outgoing(VertexId(v), [&](HalfedgeId h) {
      const auto it = path_of_edge.find(edge_key(v, mesh.head(h).idx));
      if (it != path_of_edge.end()) order.push_back(it->second);
    });
    std::rotate(order.begin(), std::min_element(order.begin(), order.end()), order.end());
  }
  return rotations;
}

/// remesh_along_paths without its fallback.
RemeshStats rebuild(RefinedMesh& refined, const Mesh& input, std::vector<std::vector<int>>& paths, bool straighten) {
  const int n_input = input.n_vertices();
  const int n_old = refined.n_vertices();
  std::vector<std::vector<int>> straight = paths;
  RemeshStats stats;
  if (straighten) stats.straightened_vertices = straighten_within_faces(refined, input, straight);
  // The vertices kept: the input vertices, then the path vertices in their old order.
  std::vector<int> new_id(static_cast<size_t>(n_old), -1);
  for (int v = 0; v < n_input; ++v) new_id[static_cast<size_t>(v)] = v;
  for (const auto& p : straight) {
    for (const int v : p) new_id[static_cast<size_t>(v)] = 0;
  }
  RefinedMesh out;
  for (int v = 0; v < n_old; ++v) {
    if (new_id[static_cast<size_t>(v)] < 0) {
      ++stats.dropped_vertices;
      continue;
    }
    new_id[static_cast<size_t>(v)] = out.n_vertices();
    out.positions.push_back(refined.positions[static_cast<size_t>(v)]);
    out.on_input.push_back(refined.on_input[static_cast<size_t>(v)]);
  }
  // Per input face: the kept vertices that are not its corners, and the path segments that cross its interior.
  const auto nf = static_cast<size_t>(input.n_faces());
  std::vector<std::vector<int>> extra(nf);
  std::vector<std::vector<std::array<int, 2>>> segments(nf);
  for (int v = n_input; v < out.n_vertices(); ++v) {
    for (const int f : faces_containing(input, out.on_input[static_cast<size_t>(v)]))
      extra[static_cast<size_t>(f)].push_back(v);
  }
  std::vector<std::vector<int>> renumbered = std::move(straight);
  for (auto& p : renumbered) {
    for (int& v : p) v = new_id[static_cast<size_t>(v)];
    for (size_t i = 0; i + 1 < p.size(); ++i) {
      const auto common =
          common_faces(input, out.on_input[static_cast<size_t>(p[i])], out.on_input[static_cast<size_t>(p[i + 1])]);
      if (common.empty())
        throw PipelineError("cut: path segment " + edge_name(p[i], p[i + 1]) + " lies in no input face");
      if (common.size() == 1) segments[static_cast<size_t>(common[0])].push_back({p[i], p[i + 1]});
    }
  }
  for (size_t f = 0; f < nf; ++f) {
    const auto c = input.face_vertices(FaceId(static_cast<int>(f)));
    if (extra[f].empty()) {
      out.faces.push_back({c[0].idx, c[1].idx, c[2].idx});
      out.input_face.push_back(static_cast<int>(f));
      continue;
    }
    std::vector<FaceVertex> vertices;
    for (int k = 0; k < 3; ++k) {
      std::array<double, 3> b{0, 0, 0};
      b[static_cast<size_t>(k)] = 1;
      vertices.push_back({c[static_cast<size_t>(k)].idx, b, sides_of(b)});
    }
    for (const int v : extra[f]) {
      const auto b = barycentric_in_face(input, out.on_input[static_cast<size_t>(v)], FaceId(static_cast<int>(f)));
      vertices.push_back({v, b, sides_of(b)});
    }
    const auto corners = layout(refined, c);
    std::vector<std::array<int, 3>> triangles;
    try {
      triangles = triangulate_face<CGAL::Epick>(corners, vertices, segments[f], static_cast<int>(f));
    } catch (const PipelineError&) {
      // Rounding put points of one side off its line (a sliver of three side points, or a gap): exactly, then.
      triangles = triangulate_face<CGAL::Epeck>(corners, vertices, segments[f], static_cast<int>(f));
      ++stats.exact_faces;
    }
    for (const auto& t : triangles) {
      out.faces.push_back(t);
      out.input_face.push_back(static_cast<int>(f));
    }
    ++stats.remeshed_faces;
  }
  out.mesh = Mesh(out.face_matrix(), out.n_vertices());
  for (const auto& p : renumbered) {
    for (size_t i = 0; i + 1 < p.size(); ++i) {
      if (!find_halfedge(out.mesh, VertexId(p[i]), VertexId(p[i + 1])).valid())
        throw PipelineError("cut: path segment " + edge_name(p[i], p[i + 1]) +
                            " is not an edge after re-triangulation");
    }
  }
  // Straightened chords from a vertex inside an input face can leave it in another order than the traced paths
  // (seen with surface-point landmarks and a clearance of 5% of the input edge): the two meshes' cuts would no
  // longer correspond. Renumbered ends keep their order only if the embedding of the tree is unchanged.
  if (straighten) {
    std::map<int, std::vector<int>> before;
    for (auto& [v, order] : path_rotations(refined.mesh, paths)) before[new_id[static_cast<size_t>(v)]] = order;
    if (before != path_rotations(out.mesh, renumbered))
      throw PipelineError("cut: straightened paths meet a landmark in another order");
  }
  refined = std::move(out);
  paths = std::move(renumbered);
  return stats;
}

}  // namespace

RemeshStats remesh_along_paths(RefinedMesh& refined, const Mesh& input, std::vector<std::vector<int>>& paths,
                               bool straighten) {
  if (straighten) {
    try {
      return rebuild(refined, input, paths, true);
    } catch (const PipelineError&) {
      // Rounding let two straightened paths touch in some face, or meet a landmark in another order: keep the
      // paths as traced.
    }
  }
  try {
    RemeshStats stats = rebuild(refined, input, paths, false);
    stats.straightening_failed = straighten;
    return stats;
  } catch (const PipelineError&) {
    // Two refined vertices at one point of a face (the tracing's refinements can make them): the refined mesh is
    // valid as it is, only not re-triangulated.
    RemeshStats stats;
    stats.kept_as_traced = true;
    return stats;
  }
}

}  // namespace liftmap
