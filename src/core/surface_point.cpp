#include "core/surface_point.h"

#include <algorithm>
#include <cassert>
#include <string>

#include "core/errors.h"

namespace liftmap {

SurfacePoint SurfacePoint::at_vertex(VertexId v) {
  SurfacePoint p;
  p.kind = Kind::kVertex;
  p.vertex = v;
  return p;
}

SurfacePoint SurfacePoint::on_edge(EdgeId e, double t) {
  SurfacePoint p;
  p.kind = Kind::kEdge;
  p.edge = e;
  p.t = t;
  return p;
}

SurfacePoint SurfacePoint::in_face(FaceId f, const std::array<double, 3>& bary) {
  SurfacePoint p;
  p.kind = Kind::kFace;
  p.face = f;
  p.bary = bary;
  return p;
}

Eigen::RowVectorXd interpolate(const Mesh& mesh, const Eigen::MatrixXd& X, const SurfacePoint& p) {
  switch (p.kind) {
    case SurfacePoint::Kind::kVertex:
      return X.row(p.vertex.idx);
    case SurfacePoint::Kind::kEdge: {
      const HalfedgeId h = Mesh::halfedge(p.edge);
      return (1.0 - p.t) * X.row(mesh.tail(h).idx) + p.t * X.row(mesh.head(h).idx);
    }
    case SurfacePoint::Kind::kFace: {
      const auto fv = mesh.face_vertices(p.face);
      return p.bary[0] * X.row(fv[0].idx) + p.bary[1] * X.row(fv[1].idx) + p.bary[2] * X.row(fv[2].idx);
    }
  }
  return {};
}

SurfacePoint as_face_point(const Mesh& mesh, const SurfacePoint& p) {
  if (p.kind == SurfacePoint::Kind::kFace) return p;
  HalfedgeId h;
  if (p.kind == SurfacePoint::Kind::kVertex) {
    h = mesh.halfedge(p.vertex);
  } else {
    h = Mesh::halfedge(p.edge);
    if (mesh.is_boundary(h)) h = Mesh::twin(h);
  }
  assert(h.valid() && !mesh.is_boundary(h));
  const FaceId f = mesh.face(h);
  return SurfacePoint::in_face(f, barycentric_in_face(mesh, p, f));
}

std::array<double, 3> barycentric_in_face(const Mesh& input, const SurfacePoint& p, FaceId f) {
  std::array<double, 3> b{0, 0, 0};
  const auto fh = input.face_halfedges(f);
  switch (p.kind) {
    case SurfacePoint::Kind::kVertex:
      for (int k = 0; k < 3; ++k) {
        if (input.tail(fh[k]) == p.vertex) b[k] = 1.0;
      }
      return b;
    case SurfacePoint::Kind::kEdge:
      for (int k = 0; k < 3; ++k) {
        if (Mesh::edge(fh[k]) != p.edge) continue;
        // fh[k] runs from corner k to corner k+1; edge parameter t is measured along Mesh::halfedge(edge).
        const bool same = fh[k] == Mesh::halfedge(p.edge);
        b[k] = same ? 1.0 - p.t : p.t;
        b[(k + 1) % 3] = same ? p.t : 1.0 - p.t;
      }
      return b;
    case SurfacePoint::Kind::kFace:
      return p.bary;
  }
  return b;
}

std::array<double, 3> clamp_barycentric(std::array<double, 3> w) {
  double sum = 0;
  for (double& x : w) {
    x = std::max(x, 0.0);
    sum += x;
  }
  for (double& x : w) x /= sum;
  return w;
}

std::array<double, 3> reexpress_in_face(const SurfacePoint& p, const Eigen::MatrixXi& F, int f, bool* exact) {
  if (exact != nullptr) *exact = true;
  if (p.face.idx == f) return p.bary;
  std::array<double, 3> w{0, 0, 0};
  double lost = 0;
  for (int k = 0; k < 3; ++k) {
    const double b = p.bary[static_cast<size_t>(k)];
    bool found = false;
    for (int j = 0; j < 3; ++j) {
      if (F(p.face.idx, k) == F(f, j)) {
        w[static_cast<size_t>(j)] += b;
        found = true;
      }
    }
    if (!found) lost += b;
  }
  if (lost > 1e-9) {
    if (exact != nullptr) {
      *exact = false;
      return w;
    }
    throw PipelineError("face " + std::to_string(f) + " does not hold a point of face " + std::to_string(p.face.idx) +
                        " (weight " + std::to_string(lost) + " on a vertex it does not have)");
  }
  return clamp_barycentric(w);
}

SurfacePoint canonical_point(const Mesh& mesh, FaceId f, std::array<double, 3> b) {
  b = clamp_barycentric(b);
  const int nonzero = (b[0] > 0) + (b[1] > 0) + (b[2] > 0);
  const auto fh = mesh.face_halfedges(f);
  if (nonzero == 1) {
    for (int k = 0; k < 3; ++k) {
      if (b[k] > 0) return SurfacePoint::at_vertex(mesh.tail(fh[k]));
    }
  }
  if (nonzero == 2) {
    for (int k = 0; k < 3; ++k) {
      if (b[(k + 2) % 3] > 0) continue;
      // Zero weight at corner k+2: the point is on halfedge k (corner k to corner k+1).
      const EdgeId e = Mesh::edge(fh[k]);
      const bool same = fh[k] == Mesh::halfedge(e);
      return SurfacePoint::on_edge(e, same ? b[(k + 1) % 3] : b[k]);
    }
  }
  return SurfacePoint::in_face(f, b);
}

}  // namespace liftmap
