#include "core/mesh.h"

#include <algorithm>
#include <string>
#include <tuple>
#include <vector>

#include "core/errors.h"

namespace liftmap {

namespace {

struct Corner {
  int lo, hi;   // undirected edge key
  int face, k;  // halfedge from corner k to corner k+1 of face
};

/// The corners in the order of (lo, hi, face, k): bucketed by lo (a counting sort, linear), then each bucket (about
/// six corners) sorted. The same order as one comparison sort of the whole, in a fraction of its time.
std::vector<Corner> sorted_by_edge(const std::vector<Corner>& corners, int n_vertices) {
  std::vector<int> first(static_cast<size_t>(n_vertices) + 1, 0);
  for (const Corner& c : corners) ++first[static_cast<size_t>(c.lo) + 1];
  for (size_t v = 0; v < static_cast<size_t>(n_vertices); ++v) first[v + 1] += first[v];
  std::vector<Corner> out(corners.size());
  std::vector<int> next(first.begin(), first.end() - 1);
  for (const Corner& c : corners) out[static_cast<size_t>(next[static_cast<size_t>(c.lo)]++)] = c;
  for (size_t v = 0; v < static_cast<size_t>(n_vertices); ++v) {
    std::sort(out.begin() + first[v], out.begin() + first[v + 1], [](const Corner& x, const Corner& y) {
      return std::tie(x.hi, x.face, x.k) < std::tie(y.hi, y.face, y.k);
    });
  }
  return out;
}

}  // namespace

Mesh::Mesh(const Eigen::MatrixXi& F, int n_vertices) {
  if (F.size() > 0 && F.cols() != 3) throw InvalidInputError("faces must be triangles");
  const int nf = static_cast<int>(F.rows());
  std::vector<Corner> corners;
  corners.reserve(static_cast<size_t>(3 * nf));
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int v = F(f, k);
      if (v < 0 || v >= n_vertices) {
        throw InvalidInputError("face " + std::to_string(f) + " references vertex " + std::to_string(v) +
                                " but there are " + std::to_string(n_vertices) + " vertices");
      }
    }
    if (F(f, 0) == F(f, 1) || F(f, 1) == F(f, 2) || F(f, 2) == F(f, 0)) {
      throw InvalidInputError("face " + std::to_string(f) + " repeats a vertex: (" + std::to_string(F(f, 0)) + ", " +
                              std::to_string(F(f, 1)) + ", " + std::to_string(F(f, 2)) + ")");
    }
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      corners.push_back({std::min(a, b), std::max(a, b), f, k});
    }
  }
  corners = sorted_by_edge(corners, n_vertices);

  // Halfedge of corner (f, k), assigned edge by edge so that twins are 2e, 2e+1.
  std::vector<int> corner_he(static_cast<size_t>(3 * nf), -1);
  he_tail_.clear();
  he_face_.clear();
  size_t i = 0;
  while (i < corners.size()) {
    size_t j = i + 1;
    while (j < corners.size() && corners[j].lo == corners[i].lo && corners[j].hi == corners[i].hi) ++j;
    const Corner& c0 = corners[i];
    if (j - i > 2) {
      throw InvalidInputError("edge " + edge_name(c0.lo, c0.hi) + " is shared by " + std::to_string(j - i) +
                              " faces (non-manifold edge)");
    }
    const int e = static_cast<int>(he_tail_.size() / 2);
    const int t0 = F(c0.face, c0.k);
    corner_he[static_cast<size_t>(3 * c0.face + c0.k)] = 2 * e;
    he_tail_.push_back(VertexId(t0));
    he_face_.push_back(FaceId(c0.face));
    const int t1 = t0 == c0.lo ? c0.hi : c0.lo;
    he_tail_.push_back(VertexId(t1));
    if (j - i == 2) {
      const Corner& c1 = corners[i + 1];
      if (F(c1.face, c1.k) != t1) {
        throw InvalidInputError("faces " + std::to_string(c0.face) + " and " + std::to_string(c1.face) +
                                " have inconsistent orientation across edge " + edge_name(c0.lo, c0.hi));
      }
      corner_he[static_cast<size_t>(3 * c1.face + c1.k)] = 2 * e + 1;
      he_face_.push_back(FaceId(c1.face));
    } else {
      he_face_.push_back(FaceId());
    }
    i = j;
  }

  const size_t nh = he_tail_.size();
  he_next_.assign(nh, HalfedgeId());
  he_prev_.assign(nh, HalfedgeId());
  f_halfedge_.assign(static_cast<size_t>(nf), HalfedgeId());
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int h = corner_he[static_cast<size_t>(3 * f + k)];
      const int hn = corner_he[static_cast<size_t>(3 * f + (k + 1) % 3)];
      he_next_[static_cast<size_t>(h)] = HalfedgeId(hn);
      he_prev_[static_cast<size_t>(hn)] = HalfedgeId(h);
    }
    f_halfedge_[static_cast<size_t>(f)] = HalfedgeId(corner_he[static_cast<size_t>(3 * f)]);
  }

  // Boundary loops: the boundary halfedge leaving w follows the one arriving at w.
  std::vector<int> boundary_out(static_cast<size_t>(n_vertices), -1);
  for (size_t h = 0; h < nh; ++h) {
    if (he_face_[h].valid()) continue;
    const int v = he_tail_[h].idx;
    if (boundary_out[static_cast<size_t>(v)] >= 0) {
      throw InvalidInputError("vertex " + std::to_string(v) +
                              " is non-manifold: two boundary fans meet there (bow-tie vertex)");
    }
    boundary_out[static_cast<size_t>(v)] = static_cast<int>(h);
  }
  for (size_t h = 0; h < nh; ++h) {
    if (he_face_[h].valid()) continue;
    const int w = he_tail_[h ^ 1].idx;
    const int hn = boundary_out[static_cast<size_t>(w)];
    he_next_[h] = HalfedgeId(hn);
    he_prev_[static_cast<size_t>(hn)] = HalfedgeId(static_cast<int>(h));
  }

  v_halfedge_.assign(static_cast<size_t>(n_vertices), HalfedgeId());
  std::vector<int> n_out(static_cast<size_t>(n_vertices), 0);
  for (size_t h = 0; h < nh; ++h) {
    const auto v = static_cast<size_t>(he_tail_[h].idx);
    ++n_out[v];
    if (!v_halfedge_[v].valid()) v_halfedge_[v] = HalfedgeId(static_cast<int>(h));
  }
  for (int v = 0; v < n_vertices; ++v) {
    const int b = boundary_out[static_cast<size_t>(v)];
    if (b >= 0) v_halfedge_[static_cast<size_t>(v)] = twin(he_prev_[static_cast<size_t>(b)]);
  }
  // A vertex whose outgoing halfedges do not form a single fan is non-manifold (e.g. two cones touching).
  for (int v = 0; v < n_vertices; ++v) {
    if (n_out[static_cast<size_t>(v)] != 0 && degree(VertexId(v)) != n_out[static_cast<size_t>(v)]) {
      throw InvalidInputError("vertex " + std::to_string(v) + " is non-manifold: its faces form more than one fan");
    }
  }
}

int Mesh::degree(VertexId v) const {
  int n = 0;
  for_each_outgoing(v, [&](HalfedgeId) { ++n; });
  return n;
}

std::vector<std::vector<HalfedgeId>> Mesh::boundary_loops() const {
  std::vector<std::vector<HalfedgeId>> loops;
  std::vector<char> seen(he_next_.size(), 0);
  for (int h = 0; h < n_halfedges(); ++h) {
    if (seen[static_cast<size_t>(h)] || !is_boundary(HalfedgeId(h))) continue;
    std::vector<HalfedgeId> loop;
    HalfedgeId g(h);
    do {
      seen[static_cast<size_t>(g.idx)] = 1;
      loop.push_back(g);
      g = next(g);
    } while (g.idx != h);
    loops.push_back(std::move(loop));
  }
  return loops;
}

Eigen::MatrixXi Mesh::faces() const {
  Eigen::MatrixXi F(n_faces(), 3);
  for (int f = 0; f < n_faces(); ++f) {
    const auto fv = face_vertices(FaceId(f));
    F.row(f) << fv[0].idx, fv[1].idx, fv[2].idx;
  }
  return F;
}

int Mesh::euler_characteristic() const {
  int nv = 0;
  for (int v = 0; v < n_vertices(); ++v) nv += is_isolated(VertexId(v)) ? 0 : 1;
  return nv - n_edges() + n_faces();
}

}  // namespace liftmap
