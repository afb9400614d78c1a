#include "lift/lift_path.h"

#include <algorithm>
#include <sstream>
#include <string>

#include "core/errors.h"
#include "lift/exact_predicates.h"
#include "lift/format_point.h"
#include "lift/local_injectivity.h"

namespace liftmap {

namespace {

double cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

std::string segment_name(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return "the segment from " + format_point(a) + " to " + format_point(b);
}

/// Barycentric coordinates of z = (zx, zy) in the triangle c, computed in T, from sub-triangle areas. A point that
/// rounding put outside (a negative coordinate) is moved to the nearest point of the edge it fell across; clamping
/// the coordinate to 0 and renormalising would move it along a sliver by its length times the overshoot over its
/// height (8e-12 of the mesh, seen on triceratops to man).
template <class T>
std::array<double, 3> weights_in_triangle(const std::array<Eigen::Vector2d, 3>& c, T zx, T zy) {
  std::array<T, 3> w{};
  for (size_t k = 0; k < 3; ++k) {
    const Eigen::Vector2d& u = c[(k + 1) % 3];
    const Eigen::Vector2d& v = c[(k + 2) % 3];
    w[k] = (T(u.x()) - zx) * (T(v.y()) - zy) - (T(u.y()) - zy) * (T(v.x()) - zx);
  }
  const auto k = static_cast<size_t>(std::min_element(w.begin(), w.end()) - w.begin());
  if (w[k] < 0) {  // onto the edge opposite corner k, from corner k + 1 to corner k + 2
    const Eigen::Vector2d& u = c[(k + 1) % 3];
    const Eigen::Vector2d& v = c[(k + 2) % 3];
    const T dx = T(v.x()) - u.x(), dy = T(v.y()) - u.y();
    const T len2 = dx * dx + dy * dy;
    const T t = len2 > 0 ? std::clamp(((zx - u.x()) * dx + (zy - u.y()) * dy) / len2, T(0), T(1)) : T(0);
    std::array<double, 3> out{};
    out[(k + 1) % 3] = static_cast<double>(1 - t);
    out[(k + 2) % 3] = static_cast<double>(t);
    return out;
  }
  const T sum = w[0] + w[1] + w[2];
  if (!(sum > 0)) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
  return {static_cast<double>(w[0] / sum), static_cast<double>(w[1] / sum), static_cast<double>(w[2] / sum)};
}

}  // namespace

PathLifter::PathLifter(const Mesh& mesh, const Eigen::MatrixXd& Psi) : mesh_(mesh) {
  if (Psi.rows() != mesh.n_vertices() || Psi.cols() != 2) {
    std::ostringstream s;
    s << "path lifting: flattening is " << Psi.rows() << " by " << Psi.cols() << ", expected " << mesh.n_vertices()
      << " by 2";
    throw InvalidInputError(s.str());
  }
  if (!Psi.allFinite()) throw InvalidInputError("path lifting: flattening has non-finite coordinates");
  psi_.resize(static_cast<size_t>(mesh.n_vertices()));
  for (int i = 0; i < mesh.n_vertices(); ++i) psi_[static_cast<size_t>(i)] = Psi.row(i).transpose();
  const LocalInjectivityReport report = check_local_injectivity(mesh, Psi);
  if (!report.locally_injective()) {
    std::string where = report.summary(Psi);
    if (!report.flipped_faces.empty()) {
      const FaceId f = report.flipped_faces.front();
      const auto fv = mesh.face_vertices(f);
      where += "; face " + std::to_string(f.idx) + " has vertices " + std::to_string(fv[0].idx) + " " +
               format_point(position(fv[0])) + ", " + std::to_string(fv[1].idx) + " " + format_point(position(fv[1])) +
               ", " + std::to_string(fv[2].idx) + " " + format_point(position(fv[2]));
    }
    throw PipelineError(
        "path lifting: the flattening is not locally injective, so it cannot be lifted (paper "
        "§3.2): " +
        where);
  }
  max_steps_ = mesh.n_vertices() + mesh.n_edges() + mesh.n_faces() + 4;
}

FaceId PathLifter::face_of_edge(HalfedgeId h) const {
  return mesh_.is_boundary(h) ? mesh_.face(Mesh::twin(h)) : mesh_.face(h);
}

SurfacePoint PathLifter::face_point(FaceId f, const Eigen::Vector2d& z) const {
  return SurfacePoint::in_face(f, weights_in_triangle(corners(f), z.x(), z.y()));
}

std::array<Eigen::Vector2d, 3> PathLifter::corners(FaceId f) const {
  const auto fv = mesh_.face_vertices(f);
  return {position(fv[0]), position(fv[1]), position(fv[2])};
}

SurfacePoint PathLifter::refine_coordinates(const SurfacePoint& p, long double zx, long double zy) const {
  using L = long double;
  if (p.kind == SurfacePoint::Kind::kEdge) {
    const HalfedgeId h0 = Mesh::halfedge(p.edge);
    const Eigen::Vector2d& a = position(mesh_.tail(h0));
    const Eigen::Vector2d& b = position(mesh_.head(h0));
    const L dx = L(b.x()) - a.x(), dy = L(b.y()) - a.y();
    const L t = ((zx - a.x()) * dx + (zy - a.y()) * dy) / (dx * dx + dy * dy);
    return SurfacePoint::on_edge(p.edge, std::clamp(static_cast<double>(t), 0.0, 1.0));
  }
  if (p.kind != SurfacePoint::Kind::kFace) return p;
  return SurfacePoint::in_face(p.face, weights_in_triangle(corners(p.face), zx, zy));
}

SurfacePoint PathLifter::edge_point(HalfedgeId h, const Eigen::Vector2d& z) const {
  const EdgeId e = Mesh::edge(h);
  const HalfedgeId h0 = Mesh::halfedge(e);
  const Eigen::Vector2d& p = position(mesh_.tail(h0));
  const Eigen::Vector2d d = position(mesh_.head(h0)) - p;
  return SurfacePoint::on_edge(e, std::clamp((z - p).dot(d) / d.squaredNorm(), 0.0, 1.0));
}

SurfacePoint PathLifter::refine(const SurfacePoint& hint, const Eigen::Vector2d& z) const {
  switch (hint.kind) {
    case SurfacePoint::Kind::kVertex:
      if (position(hint.vertex) == z) return SurfacePoint::at_vertex(hint.vertex);
      throw InvalidInputError("path lifting: start vertex " + std::to_string(hint.vertex.idx) + " lies at " +
                              format_point(position(hint.vertex)) + ", not at " + format_point(z));
    case SurfacePoint::Kind::kEdge: {
      const HalfedgeId h0 = Mesh::halfedge(hint.edge);
      const Eigen::Vector2d& p = position(mesh_.tail(h0));
      const Eigen::Vector2d& q = position(mesh_.head(h0));
      if (z == p) return SurfacePoint::at_vertex(mesh_.tail(h0));
      if (z == q) return SurfacePoint::at_vertex(mesh_.head(h0));
      if (orient2d(p, q, z) == 0 && compare_xy(p, z) == compare_xy(z, q)) return edge_point(h0, z);
      throw InvalidInputError("path lifting: " + format_point(z) + " does not lie on start edge " +
                              std::to_string(hint.edge.idx) + " from " + format_point(p) + " to " + format_point(q));
    }
    case SurfacePoint::Kind::kFace: {
      const auto fh = mesh_.face_halfedges(hint.face);
      const TriangleLocation loc =
          locate_in_triangle(position(mesh_.tail(fh[0])), position(mesh_.tail(fh[1])), position(mesh_.tail(fh[2])), z);
      switch (loc.kind) {
        case TriangleLocation::Kind::kInside:
          return face_point(hint.face, z);
        case TriangleLocation::Kind::kOnEdge:
          return edge_point(fh[static_cast<size_t>(loc.index)], z);
        case TriangleLocation::Kind::kAtVertex:
          return SurfacePoint::at_vertex(mesh_.tail(fh[static_cast<size_t>(loc.index)]));
        case TriangleLocation::Kind::kOutside:
          break;
      }
      throw InvalidInputError("path lifting: " + format_point(z) + " does not lie in start face " +
                              std::to_string(hint.face.idx));
    }
  }
  throw InvalidInputError("path lifting: invalid start point");
}

SurfacePoint PathLifter::lift_segment(const SurfacePoint& start, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                      LiftTrace* trace) const {
  const SurfacePoint first = refine(start, a);
  if (trace != nullptr) {
    trace->nodes.assign(1, first);
    trace->s.assign(1, 0.0);
    trace->faces.clear();
  }
  if (a == b) return first;

  // Every decision below is an exact predicate on a, b and vertices of Psi; `param` only feeds the trace.
  const int dir = compare_xy(a, b);
  const Eigen::Vector2d ab = b - a;
  const double ab2 = ab.squaredNorm();
  auto param = [&](const Eigen::Vector2d& p) { return std::clamp((p - a).dot(ab) / ab2, 0.0, 1.0); };
  auto record = [&](const SurfacePoint& node, double s, FaceId piece) {
    if (trace == nullptr) return;
    trace->faces.push_back(piece);
    trace->nodes.push_back(node);
    trace->s.push_back(std::max(s, trace->s.back()));
  };
  auto leave_error = [&](const std::string& where) {
    return PipelineError("path lifting: the walk along " + segment_name(a, b) + " leaves the disk through " + where +
                         ": the flattenings are not liftable (paper §3.2)");
  };

  // Walk state: at a vertex, moving along a halfedge towards its head, or inside a face.
  enum class State { kVertex, kAlong, kFace };
  State state = State::kFace;
  VertexId vertex;
  HalfedgeId along;
  FaceId face;
  switch (first.kind) {
    case SurfacePoint::Kind::kVertex:
      state = State::kVertex;
      vertex = first.vertex;
      break;
    case SurfacePoint::Kind::kEdge: {
      const HalfedgeId h0 = Mesh::halfedge(first.edge);
      const Eigen::Vector2d& p = position(mesh_.tail(h0));
      const Eigen::Vector2d& q = position(mesh_.head(h0));
      const int o = orient2d(p, q, b);
      if (o == 0) {
        state = State::kAlong;
        along = compare_xy(p, q) == dir ? h0 : Mesh::twin(h0);
      } else {
        const HalfedgeId h = o > 0 ? h0 : Mesh::twin(h0);
        if (mesh_.is_boundary(h)) {
          throw leave_error("boundary edge " + std::to_string(first.edge.idx) + " (vertices " +
                            std::to_string(mesh_.tail(h0).idx) + ", " + std::to_string(mesh_.head(h0).idx) +
                            ") at its start " + format_point(a));
        }
        state = State::kFace;
        face = mesh_.face(h);
      }
      break;
    }
    case SurfacePoint::Kind::kFace:
      state = State::kFace;
      face = first.face;
      break;
  }

  for (int step = 0; step < max_steps_; ++step) {
    switch (state) {
      case State::kFace: {
        const auto fh = mesh_.face_halfedges(face);
        const std::array<const Eigen::Vector2d*, 3> P = {&position(mesh_.tail(fh[0])), &position(mesh_.tail(fh[1])),
                                                         &position(mesh_.tail(fh[2]))};
        const TriangleLocation end = locate_in_triangle(*P[0], *P[1], *P[2], b);
        if (end.kind != TriangleLocation::Kind::kOutside) {
          SurfacePoint result;
          if (end.kind == TriangleLocation::Kind::kInside) {
            result = face_point(face, b);
          } else if (end.kind == TriangleLocation::Kind::kOnEdge) {
            result = edge_point(fh[static_cast<size_t>(end.index)], b);
          } else {
            result = SurfacePoint::at_vertex(mesh_.tail(fh[static_cast<size_t>(end.index)]));
          }
          record(result, 1.0, face);
          return result;
        }
        // Sides of the corners w.r.t. the line a->b. Going counter-clockwise around the face, the walk leaves
        // where the corners pass from right (< 0) to left (> 0) of the line: through an edge, or a corner on it.
        const std::array<int, 3> s = {orient2d(a, b, *P[0]), orient2d(a, b, *P[1]), orient2d(a, b, *P[2])};
        bool moved = false;
        for (size_t k = 0; k < 3 && !moved; ++k) {
          const size_t k1 = (k + 1) % 3;
          const size_t k2 = (k + 2) % 3;
          if (s[k] < 0 && s[k1] > 0) {
            const HalfedgeId out = Mesh::twin(fh[k]);
            if (trace != nullptr) {
              const double sa = cross(ab, *P[k] - a);
              const double sb = cross(ab, *P[k1] - a);
              const Eigen::Vector2d x = *P[k] + (sa / (sa - sb)) * (*P[k1] - *P[k]);
              record(edge_point(fh[k], x), param(x), face);
            }
            if (mesh_.is_boundary(out)) {
              throw leave_error("boundary edge " + std::to_string(Mesh::edge(out).idx) + " (vertices " +
                                std::to_string(mesh_.tail(fh[k]).idx) + " at " + format_point(*P[k]) + ", " +
                                std::to_string(mesh_.tail(fh[k1]).idx) + " at " + format_point(*P[k1]) + ") of face " +
                                std::to_string(face.idx));
            }
            face = mesh_.face(out);
            moved = true;
          } else if (s[k] == 0 && s[k2] < 0 && s[k1] > 0) {
            vertex = mesh_.tail(fh[k]);
            record(SurfacePoint::at_vertex(vertex), param(*P[k]), face);
            state = State::kVertex;
            moved = true;
          }
        }
        if (!moved) {
          throw PipelineError("path lifting: internal error, no exit from face " + std::to_string(face.idx) +
                              " along " + segment_name(a, b));
        }
        break;
      }
      case State::kVertex: {
        const Eigen::Vector2d& pv = position(vertex);
        if (pv == b) return SurfacePoint::at_vertex(vertex);
        // The walk passes exactly through pv, so the side of a neighbour w.r.t. the line a->b is its side
        // w.r.t. the ray from pv towards b. Exactly one fan wedge (or edge) holds that ray.
        bool moved = false;
        const HalfedgeId first_out = mesh_.halfedge(vertex);
        HalfedgeId h = first_out;
        do {
          const Eigen::Vector2d& pw = position(mesh_.head(h));
          const int sw = orient2d(a, b, pw);
          if (sw == 0 && compare_xy(pv, pw) == dir) {
            state = State::kAlong;
            along = h;
            moved = true;
          } else if (sw < 0 && !mesh_.is_boundary(h) && orient2d(a, b, position(mesh_.head(mesh_.next(h)))) > 0) {
            state = State::kFace;
            face = mesh_.face(h);
            moved = true;
          }
          h = mesh_.rotate_ccw(h);
        } while (!moved && h != first_out);
        if (!moved) {
          if (mesh_.is_boundary(vertex)) {
            throw leave_error("boundary vertex " + std::to_string(vertex.idx) + " at " + format_point(pv));
          }
          throw PipelineError("path lifting: internal error, no fan wedge of vertex " + std::to_string(vertex.idx) +
                              " at " + format_point(pv) + " holds " + segment_name(a, b));
        }
        break;
      }
      case State::kAlong: {
        const VertexId w = mesh_.head(along);
        const Eigen::Vector2d& pw = position(w);
        const FaceId piece = face_of_edge(along);
        if (pw == b) {
          const SurfacePoint result = SurfacePoint::at_vertex(w);
          record(result, 1.0, piece);
          return result;
        }
        if (compare_xy(b, pw) == dir) {  // b comes before w along the edge
          const SurfacePoint result = edge_point(along, b);
          record(result, 1.0, piece);
          return result;
        }
        record(SurfacePoint::at_vertex(w), param(pw), piece);
        state = State::kVertex;
        vertex = w;
        break;
      }
    }
  }
  std::ostringstream s;
  s << "path lifting: the walk along " << segment_name(a, b) << " did not end within " << max_steps_
    << " steps (a straight segment meets each element of a locally injective flattening at most once)";
  throw PipelineError(s.str());
}

LiftedPath PathLifter::lift_polyline(const SurfacePoint& start, const Eigen::MatrixXd& W) const {
  if (W.rows() == 0 || W.cols() != 2) throw InvalidInputError("path lifting: the polyline must be #W by 2, #W >= 1");
  LiftedPath path;
  Eigen::Vector2d a = W.row(0).transpose();
  path.points.push_back(refine(start, a));
  path.row_index.push_back(0);
  LiftTrace trace;
  for (Eigen::Index i = 1; i < W.rows(); ++i) {
    const Eigen::Vector2d b = W.row(i).transpose();
    lift_segment(path.points.back(), a, b, &trace);
    path.points.insert(path.points.end(), trace.nodes.begin() + 1, trace.nodes.end());
    path.row_index.push_back(static_cast<int>(path.points.size()) - 1);
    a = b;
  }
  return path;
}

LiftedPath lift_path(const Mesh& mesh, const Eigen::MatrixXd& Psi, const SurfacePoint& start,
                     const Eigen::MatrixXd& W) {
  return PathLifter(mesh, Psi).lift_polyline(start, W);
}

}  // namespace liftmap
