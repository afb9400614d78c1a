#include "lift/local_injectivity.h"

#include <sstream>

#include "core/errors.h"
#include "lift/exact_predicates.h"
#include "lift/format_point.h"

namespace liftmap {

namespace {

Eigen::Vector2d point(const Eigen::MatrixXd& X, VertexId v) { return X.row(v.idx).transpose(); }

/// Number of times the fan of `v` sweeps past the direction of its first outgoing edge (counter-clockwise,
/// excluding the start). 1 for a locally injective interior vertex, 0 for a boundary vertex with angle < 2*pi.
/// \pre every face around `v` is counter-clockwise.
int count_sweeps(const Mesh& mesh, const Eigen::MatrixXd& X, VertexId v) {
  const Eigen::Vector2d pv = point(X, v);
  const Eigen::Vector2d r = point(X, mesh.head(mesh.halfedge(v)));
  const int r_dir = compare_xy(pv, r);
  int count = 0;
  mesh.for_each_outgoing(v, [&](HalfedgeId h) {
    if (mesh.is_boundary(h)) return;
    // Wedge of the face left of h, from u to u2 counter-clockwise, less than pi wide.
    const Eigen::Vector2d u = point(X, mesh.head(h));
    const Eigen::Vector2d u2 = point(X, mesh.head(mesh.next(h)));
    const int o2 = orient2d(pv, r, u2);
    const bool strictly_inside = orient2d(pv, r, u) < 0 && o2 > 0;
    const bool along_end = o2 == 0 && compare_xy(pv, u2) == r_dir;
    if (strictly_inside || along_end) ++count;
  });
  return count;
}

}  // namespace

std::string LocalInjectivityReport::summary(const Eigen::MatrixXd& X) const {
  if (locally_injective()) return {};
  std::ostringstream s;
  if (!flipped_faces.empty()) {
    s << flipped_faces.size() << " flipped or degenerate face(s), first: face " << flipped_faces.front().idx << "; ";
  }
  if (!bad_interior_vertices.empty()) {
    const int v = bad_interior_vertices.front().idx;
    s << bad_interior_vertices.size() << " interior vertex(es) whose one-ring does not wind exactly once (fold or "
      << "branch point), first: vertex " << v << " at " << format_point(point(X, VertexId(v))) << "; ";
  }
  if (!bad_boundary_vertices.empty()) {
    const int v = bad_boundary_vertices.front().idx;
    s << bad_boundary_vertices.size() << " boundary vertex(es) with angle sum >= 2*pi, first: vertex " << v << " at "
      << format_point(point(X, VertexId(v))) << "; ";
  }
  std::string out = s.str();
  out.resize(out.size() - 2);
  return out;
}

LocalInjectivityReport check_local_injectivity(const Mesh& mesh, const Eigen::MatrixXd& X) {
  if (X.rows() != mesh.n_vertices() || X.cols() != 2) {
    std::ostringstream s;
    s << "check_local_injectivity: flattening is " << X.rows() << " by " << X.cols() << ", expected "
      << mesh.n_vertices() << " by 2";
    throw InvalidInputError(s.str());
  }
  LocalInjectivityReport report;
  VertexData<char> near_flipped(mesh.n_vertices(), 0);
  for (int i = 0; i < mesh.n_faces(); ++i) {
    const FaceId f(i);
    const auto fv = mesh.face_vertices(f);
    if (orient2d(point(X, fv[0]), point(X, fv[1]), point(X, fv[2])) <= 0) {
      report.flipped_faces.push_back(f);
      for (VertexId v : fv) near_flipped[v] = 1;
    }
  }
  for (int i = 0; i < mesh.n_vertices(); ++i) {
    const VertexId v(i);
    // The sweep count assumes counter-clockwise faces; vertices at flipped faces are already reported.
    if (mesh.is_isolated(v) || near_flipped[v]) continue;
    const int sweeps = count_sweeps(mesh, X, v);
    if (mesh.is_boundary(v)) {
      if (sweeps != 0) report.bad_boundary_vertices.push_back(v);
    } else if (sweeps != 1) {
      report.bad_interior_vertices.push_back(v);
    }
  }
  return report;
}

}  // namespace liftmap
