#include "cut/refined_mesh.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <iterator>
#include <string>

#include "core/errors.h"

namespace liftmap {

namespace {

/// A vertex of a face polygon: its refined id and the set of sides of the original triangle it lies on
/// (bit k: halfedge k, from corner k to corner k+1).
struct PolyVertex {
  int id;
  unsigned sides;
};

bool collinear(const PolyVertex& a, const PolyVertex& b, const PolyVertex& c) {
  return (a.sides & b.sides & c.sides) != 0;
}

/// Ear-clips a convex polygon whose vertices lie on the sides of one triangle, never making a triangle of
/// three collinear points or a triangle with a polygon vertex on one of its sides.
void triangulate_convex(std::vector<PolyVertex> poly, int input_face, RefinedMesh& out) {
  while (poly.size() > 3) {
    const size_t n = poly.size();
    bool clipped = false;
    for (size_t i = 0; i < n && !clipped; ++i) {
      const PolyVertex& u = poly[(i + n - 1) % n];
      const PolyVertex& v = poly[i];
      const PolyVertex& w = poly[(i + 1) % n];
      if (collinear(u, v, w)) continue;
      // The diagonal u-w must not pass through another vertex: that happens only along a triangle side.
      bool blocked = false;
      for (size_t j = 0; j < n; ++j) {
        if (j == i || j == (i + n - 1) % n || j == (i + 1) % n) continue;
        if (collinear(u, w, poly[j])) blocked = true;
      }
      if (blocked) continue;
      out.faces.push_back({u.id, v.id, w.id});
      out.input_face.push_back(input_face);
      poly.erase(poly.begin() + static_cast<std::ptrdiff_t>(i));
      clipped = true;
    }
    if (!clipped) throw PipelineError("cut: cannot triangulate a refined face polygon");
  }
  if (poly.size() == 3) {
    out.faces.push_back({poly[0].id, poly[1].id, poly[2].id});
    out.input_face.push_back(input_face);
  }
}

}  // namespace

Eigen::MatrixXd RefinedMesh::vertex_matrix() const {
  Eigen::MatrixXd V(n_vertices(), 3);
  for (int i = 0; i < n_vertices(); ++i) V.row(i) = positions[static_cast<size_t>(i)].transpose();
  return V;
}

Eigen::MatrixXi RefinedMesh::face_matrix() const {
  Eigen::MatrixXi F(static_cast<int>(faces.size()), 3);
  for (size_t f = 0; f < faces.size(); ++f) {
    F.row(static_cast<int>(f)) << faces[f][0], faces[f][1], faces[f][2];
  }
  return F;
}

RefinedMesh make_refined_mesh(const Mesh& input, const Eigen::MatrixXd& V) {
  RefinedMesh r;
  const int nv = static_cast<int>(V.rows());
  r.positions.resize(static_cast<size_t>(nv));
  r.on_input.resize(static_cast<size_t>(nv));
  for (int v = 0; v < nv; ++v) {
    r.positions[static_cast<size_t>(v)] = V.row(v).transpose();
    r.on_input[static_cast<size_t>(v)] = SurfacePoint::at_vertex(VertexId(v));
  }
  for (int f = 0; f < input.n_faces(); ++f) {
    const auto fv = input.face_vertices(FaceId(f));
    r.faces.push_back({fv[0].idx, fv[1].idx, fv[2].idx});
    r.input_face.push_back(f);
  }
  r.mesh = input;
  return r;
}

HalfedgeId find_halfedge(const Mesh& mesh, VertexId a, VertexId b) {
  HalfedgeId found;
  mesh.for_each_outgoing(a, [&](HalfedgeId h) {
    if (mesh.head(h) == b) found = h;
  });
  return found;
}

void split_refined_mesh(RefinedMesh& refined, const Mesh& input, const std::vector<EdgeSplit>& splits,
                        const std::vector<std::array<int, 2>>& chords) {
  if (splits.empty() && chords.empty()) return;
  const Mesh& mesh = refined.mesh;
  const int n_old = refined.n_vertices();

  // Points on each edge, as (t along Mesh::halfedge(e), id).
  std::vector<std::vector<std::pair<double, int>>> on_edge(static_cast<size_t>(mesh.n_edges()));
  std::vector<EdgeId> split_edge(splits.size());
  for (size_t i = 0; i < splits.size(); ++i) {
    const EdgeSplit& s = splits[i];
    const HalfedgeId h = find_halfedge(mesh, VertexId(s.a), VertexId(s.b));
    if (!h.valid()) {
      throw PipelineError("cut: no refined edge " + edge_name(s.a, s.b) + " to split");
    }
    const EdgeId e = Mesh::edge(h);
    const double t = h == Mesh::halfedge(e) ? s.t : 1.0 - s.t;
    const int id = n_old + static_cast<int>(i);
    on_edge[static_cast<size_t>(e.idx)].emplace_back(t, id);
    split_edge[i] = e;
    const Eigen::Vector3d& pa = refined.positions[static_cast<size_t>(s.a)];
    const Eigen::Vector3d& pb = refined.positions[static_cast<size_t>(s.b)];
    refined.positions.push_back((1.0 - s.t) * pa + s.t * pb);
    // Provenance: both ends lie on the input face of a refined face at this edge.
    HalfedgeId hf = mesh.is_boundary(h) ? Mesh::twin(h) : h;
    const FaceId f_in(refined.input_face[static_cast<size_t>(mesh.face(hf).idx)]);
    const auto ba = barycentric_in_face(input, refined.on_input[static_cast<size_t>(s.a)], f_in);
    const auto bb = barycentric_in_face(input, refined.on_input[static_cast<size_t>(s.b)], f_in);
    std::array<double, 3> b{};
    for (int k = 0; k < 3; ++k)
      b[static_cast<size_t>(k)] = (1.0 - s.t) * ba[static_cast<size_t>(k)] + s.t * bb[static_cast<size_t>(k)];
    refined.on_input.push_back(canonical_point(input, f_in, b));
  }
  for (auto& pts : on_edge) std::sort(pts.begin(), pts.end());

  // Faces touched by a split or a chord get a polygon; the others are kept.
  const int nf = mesh.n_faces();
  std::vector<char> touched(static_cast<size_t>(nf), 0);
  for (const EdgeId e : split_edge) {
    for (const HalfedgeId h : {Mesh::halfedge(e), Mesh::twin(Mesh::halfedge(e))}) {
      if (!mesh.is_boundary(h)) touched[static_cast<size_t>(mesh.face(h).idx)] = 1;
    }
  }
  auto polygon = [&](FaceId f) {
    std::vector<PolyVertex> poly;
    const auto fh = mesh.face_halfedges(f);
    for (unsigned k = 0; k < 3; ++k) {
      poly.push_back({mesh.tail(fh[k]).idx, (1u << k) | (1u << ((k + 2) % 3))});
      const EdgeId e = Mesh::edge(fh[k]);
      const auto& pts = on_edge[static_cast<size_t>(e.idx)];
      if (fh[k] == Mesh::halfedge(e)) {
        for (const auto& pt : pts) poly.push_back({pt.second, 1u << k});
      } else {
        for (auto it = pts.rbegin(); it != pts.rend(); ++it) poly.push_back({it->second, 1u << k});
      }
    }
    return poly;
  };

  // Faces around a vertex id (old vertex: its fan; new vertex: the faces of its edge).
  auto faces_at = [&](int id) {
    std::vector<FaceId> fs;
    if (id < n_old) {
      mesh.for_each_outgoing(VertexId(id), [&](HalfedgeId h) {
        if (!mesh.is_boundary(h)) fs.push_back(mesh.face(h));
      });
    } else {
      const EdgeId e = split_edge[static_cast<size_t>(id - n_old)];
      for (const HalfedgeId h : {Mesh::halfedge(e), Mesh::twin(Mesh::halfedge(e))}) {
        if (!mesh.is_boundary(h)) fs.push_back(mesh.face(h));
      }
    }
    return fs;
  };
  std::vector<std::vector<std::array<int, 2>>> face_chords(static_cast<size_t>(nf));
  for (const auto& c : chords) {
    bool placed = false;
    for (const FaceId f : faces_at(c[0])) {
      const auto poly = polygon(f);
      const auto i0 = std::find_if(poly.begin(), poly.end(), [&](const PolyVertex& p) { return p.id == c[0]; });
      const auto i1 = std::find_if(poly.begin(), poly.end(), [&](const PolyVertex& p) { return p.id == c[1]; });
      if (i1 == poly.end()) continue;
      placed = true;
      if ((i0->sides & i1->sides) != 0) break;  // along a side: an edge already or after splitting
      face_chords[static_cast<size_t>(f.idx)].push_back(c);
      touched[static_cast<size_t>(f.idx)] = 1;
      break;
    }
    if (!placed) throw PipelineError("cut: segment " + edge_name(c[0], c[1]) + " lies in no refined face");
  }

  std::vector<std::array<int, 3>> old_faces;
  std::vector<int> old_input;
  old_faces.swap(refined.faces);
  old_input.swap(refined.input_face);
  for (int f = 0; f < nf; ++f) {
    const int in = old_input[static_cast<size_t>(f)];
    if (!touched[static_cast<size_t>(f)]) {
      refined.faces.push_back(old_faces[static_cast<size_t>(f)]);
      refined.input_face.push_back(in);
      continue;
    }
    // Split the polygon along its chords, then ear-clip the convex pieces.
    std::vector<std::vector<PolyVertex>> pieces{polygon(FaceId(f))};
    for (const auto& c : face_chords[static_cast<size_t>(f)]) {
      for (size_t p = 0; p < pieces.size(); ++p) {
        auto& poly = pieces[p];
        const auto pos = [&](int id) {
          for (size_t i = 0; i < poly.size(); ++i) {
            if (poly[i].id == id) return static_cast<std::ptrdiff_t>(i);
          }
          return std::ptrdiff_t{-1};
        };
        std::ptrdiff_t i0 = pos(c[0]), i1 = pos(c[1]);
        if (i0 < 0 || i1 < 0) continue;
        if (i0 > i1) std::swap(i0, i1);
        const auto n = static_cast<std::ptrdiff_t>(poly.size());
        if (i1 - i0 == 1 || (i0 == 0 && i1 == n - 1)) break;  // already a side
        std::vector<PolyVertex> a(poly.begin() + i0, poly.begin() + i1 + 1);
        std::vector<PolyVertex> b(poly.begin() + i1, poly.end());
        b.insert(b.end(), poly.begin(), poly.begin() + i0 + 1);
        poly = std::move(a);
        pieces.push_back(std::move(b));
        break;
      }
    }
    for (auto& piece : pieces) triangulate_convex(std::move(piece), in, refined);
  }
  refined.mesh = Mesh(refined.face_matrix(), refined.n_vertices());
}

namespace {

/// Faces of the refined mesh containing a vertex or edge point, sorted.
std::vector<int> point_faces(const Mesh& mesh, const SurfacePoint& p) {
  std::vector<int> fs;
  if (p.kind == SurfacePoint::Kind::kVertex) {
    mesh.for_each_outgoing(p.vertex, [&](HalfedgeId h) {
      if (!mesh.is_boundary(h)) fs.push_back(mesh.face(h).idx);
    });
  } else if (p.kind == SurfacePoint::Kind::kEdge) {
    for (const HalfedgeId h : {Mesh::halfedge(p.edge), Mesh::twin(Mesh::halfedge(p.edge))}) {
      if (!mesh.is_boundary(h)) fs.push_back(mesh.face(h).idx);
    }
  }
  std::sort(fs.begin(), fs.end());
  return fs;
}

}  // namespace

std::vector<int> insert_polyline(RefinedMesh& refined, const Mesh& input, const std::vector<SurfacePoint>& points) {
  const Mesh& mesh = refined.mesh;
  for (size_t i = 0; i + 1 < points.size(); ++i) {
    const auto fa = point_faces(mesh, points[i]), fb = point_faces(mesh, points[i + 1]);
    std::vector<int> common;
    std::set_intersection(fa.begin(), fa.end(), fb.begin(), fb.end(), std::back_inserter(common));
    if (common.empty()) return {};
  }
  std::vector<std::pair<int, double>> seen;
  for (const SurfacePoint& p : points) {
    if (p.kind == SurfacePoint::Kind::kEdge) seen.emplace_back(p.edge.idx, p.t);
  }
  std::sort(seen.begin(), seen.end());
  if (std::adjacent_find(seen.begin(), seen.end()) != seen.end()) return {};
  std::vector<EdgeSplit> splits;
  std::vector<int> ids;
  const int n_old = refined.n_vertices();
  for (const SurfacePoint& p : points) {
    if (p.kind == SurfacePoint::Kind::kVertex) {
      ids.push_back(p.vertex.idx);
      continue;
    }
    const HalfedgeId h = Mesh::halfedge(p.edge);
    ids.push_back(n_old + static_cast<int>(splits.size()));
    splits.push_back({mesh.tail(h).idx, mesh.head(h).idx, p.t});
  }
  std::vector<std::array<int, 2>> chords;
  bool all_edges = splits.empty();
  for (size_t i = 0; i + 1 < ids.size(); ++i) {
    if (ids[i] == ids[i + 1]) continue;
    chords.push_back({ids[i], ids[i + 1]});
    all_edges = all_edges && find_halfedge(mesh, VertexId(ids[i]), VertexId(ids[i + 1])).valid();
  }
  if (all_edges) return ids;
  split_refined_mesh(refined, input, splits, chords);
  return ids;
}

}  // namespace liftmap
