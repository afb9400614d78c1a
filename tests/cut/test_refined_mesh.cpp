#include "cut/refined_mesh.h"
#include "cut/remesh_along_paths.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <set>

#include "cut_test_util.h"

namespace liftmap {
namespace {

/// One round of splits: of `tries` random faces, each one whose neighbourhood this round has not touched yet (at most
/// one chord per face) gets split_face(halfedges, id of the next new vertex, splits, chords); then the splits are
/// made. Returns the round's chords.
template <class SplitFace>
std::vector<std::array<int, 2>> split_random_faces(RefinedMesh& r, const Mesh& input, std::mt19937& rng, int tries,
                                                   SplitFace&& split_face) {
  std::vector<EdgeSplit> splits;
  std::vector<std::array<int, 2>> chords;
  std::vector<char> face_used(static_cast<size_t>(r.mesh.n_faces()), 0);
  const int n_old = r.n_vertices();
  for (int i = 0; i < tries; ++i) {
    const FaceId f(static_cast<int>(rng() % static_cast<unsigned>(r.mesh.n_faces())));
    const auto fh = r.mesh.face_halfedges(f);
    bool busy = face_used[static_cast<size_t>(f.idx)] != 0;
    for (const HalfedgeId h : fh) busy = busy || face_used[static_cast<size_t>(r.mesh.face(Mesh::twin(h)).idx)];
    if (busy) continue;
    face_used[static_cast<size_t>(f.idx)] = 1;
    for (const HalfedgeId h : fh) face_used[static_cast<size_t>(r.mesh.face(Mesh::twin(h)).idx)] = 1;
    split_face(fh, n_old + static_cast<int>(splits.size()), splits, chords);
  }
  split_refined_mesh(r, input, splits, chords);
  return chords;
}

/// Every refined vertex is at the point of the input surface its provenance names.
void expect_exact_provenance(const RefinedMesh& r, const Mesh& input, const Eigen::MatrixXd& V) {
  const double scale = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  for (int v = 0; v < r.n_vertices(); ++v) {
    EXPECT_LT(
        (interpolate(input, V, r.on_input[static_cast<size_t>(v)]) - r.positions[static_cast<size_t>(v)].transpose())
            .norm(),
        1e-12 * scale);
  }
}

// Random edge splits and chords keep the surface: same area, closed genus 0, provenance on the input.
TEST(cut_refined_mesh, RandomSplitsKeepTheSurface) {
  const auto in = test::load("hand");
  const Mesh input(in.F, static_cast<int>(in.V.rows()));
  RefinedMesh r = make_refined_mesh(input, in.V);
  std::mt19937 rng(7);
  for (int round = 0; round < 5; ++round) {
    const auto chords = split_random_faces(r, input, rng, 200, [&](const auto& fh, int id0, auto& splits, auto& ch) {
      // Split two edges of f at random points and join them; three points on the third edge, no chord.
      const double t0 = std::uniform_real_distribution<double>(0.05, 0.95)(rng);
      const double t1 = std::uniform_real_distribution<double>(0.05, 0.95)(rng);
      splits.push_back({r.mesh.tail(fh[0]).idx, r.mesh.head(fh[0]).idx, t0});
      splits.push_back({r.mesh.tail(fh[1]).idx, r.mesh.head(fh[1]).idx, t1});
      ch.push_back({id0, id0 + 1});
      for (const double t : {0.2, 0.5, 0.7}) splits.push_back({r.mesh.tail(fh[2]).idx, r.mesh.head(fh[2]).idx, t});
    });
    for (const auto& c : chords) {
      EXPECT_TRUE(find_halfedge(r.mesh, VertexId(c[0]), VertexId(c[1])).valid());
    }
  }
  EXPECT_EQ(r.mesh.euler_characteristic(), 2);
  EXPECT_TRUE(r.mesh.boundary_loops().empty());
  EXPECT_NEAR(test::area(r.vertex_matrix(), r.face_matrix()), test::area(in.V, in.F), 1e-9 * test::area(in.V, in.F));
  expect_exact_provenance(r, input, in.V);
  // No degenerate face.
  for (const auto& f : r.faces) {
    const Eigen::Vector3d a = r.positions[static_cast<size_t>(f[0])], b = r.positions[static_cast<size_t>(f[1])],
                          c = r.positions[static_cast<size_t>(f[2])];
    EXPECT_GT((b - a).cross(c - a).norm(), 0.0);
  }
}

/// The largest angle of refined face f, in degrees.
double largest_angle(const RefinedMesh& r, const std::array<int, 3>& f) {
  double largest = 0;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d p = r.positions[static_cast<size_t>(f[static_cast<size_t>(k)])];
    const Eigen::Vector3d u = r.positions[static_cast<size_t>(f[static_cast<size_t>((k + 1) % 3)])] - p;
    const Eigen::Vector3d v = r.positions[static_cast<size_t>(f[static_cast<size_t>((k + 2) % 3)])] - p;
    largest = std::max(largest, std::atan2(u.cross(v).norm(), u.dot(v)) * 180 / std::numbers::pi);
  }
  return largest;
}

// Splits near the corners of input faces, joined by chords (as cut paths near vertices make them), leave caps and
// vertices on no path; the constrained Delaunay re-triangulation of each input face removes both and keeps the
// surface: the input vertices and the path vertices only, every face inside its input face, the same area, every
// path segment still an edge, every edge inside one input face locally Delaunay unless it is a path segment.
TEST(cut_refined_mesh, RemeshAlongPathsRemovesCapsAndKeepsTheSurface) {
  const auto in = test::load("hand");
  const Mesh input(in.F, static_cast<int>(in.V.rows()));
  RefinedMesh r = make_refined_mesh(input, in.V);
  std::mt19937 rng(11);
  std::vector<std::vector<int>> paths;
  for (int round = 0; round < 3; ++round) {
    const auto chords = split_random_faces(r, input, rng, 300, [&](const auto& fh, int id0, auto& splits, auto& ch) {
      // A chord cutting off corner 1 of the face close to it, and a point near the end of the third edge.
      const double near = std::uniform_real_distribution<double>(0.01, 0.05)(rng);
      splits.push_back({r.mesh.tail(fh[0]).idx, r.mesh.head(fh[0]).idx, 1 - near});
      splits.push_back({r.mesh.tail(fh[1]).idx, r.mesh.head(fh[1]).idx, near});
      splits.push_back({r.mesh.tail(fh[2]).idx, r.mesh.head(fh[2]).idx, 0.5 + near});
      ch.push_back({id0, id0 + 1});
    });
    for (const auto& c : chords) paths.push_back({c[0], c[1]});
  }
  // Chords that later rounds split are no edges any more: the others are the paths.
  std::erase_if(
      paths, [&](const std::vector<int>& p) { return !find_halfedge(r.mesh, VertexId(p[0]), VertexId(p[1])).valid(); });
  ASSERT_GT(paths.size(), 300u);
  const RefinedMesh before = r;
  std::vector<std::vector<Eigen::Vector3d>> path_points;
  std::set<int> path_vertices;
  for (const auto& p : paths) {
    path_points.push_back({r.positions[static_cast<size_t>(p[0])], r.positions[static_cast<size_t>(p[1])]});
    path_vertices.insert(p.begin(), p.end());
  }
  auto caps = [](const RefinedMesh& m) {
    int n = 0;
    for (const auto& f : m.faces) n += largest_angle(m, f) > 170 ? 1 : 0;
    return n;
  };
  const RemeshStats stats = remesh_along_paths(r, input, paths);
  ASSERT_GT(caps(before), 50);
  EXPECT_LT(2 * caps(r), caps(before)) << "caps before " << caps(before) << ", after " << caps(r);

  // Only the input vertices and the path vertices are left, at the same points, and the paths are the same.
  EXPECT_EQ(r.n_vertices(), in.V.rows() + static_cast<Eigen::Index>(path_vertices.size()));
  EXPECT_EQ(stats.dropped_vertices, before.n_vertices() - r.n_vertices());
  EXPECT_GT(stats.dropped_vertices, 0);
  for (size_t i = 0; i < paths.size(); ++i) {
    for (size_t j = 0; j < 2; ++j) EXPECT_EQ(r.positions[static_cast<size_t>(paths[i][j])], path_points[i][j]);
  }
  EXPECT_EQ(r.mesh.euler_characteristic(), 2);
  EXPECT_TRUE(r.mesh.boundary_loops().empty());
  EXPECT_NEAR(test::area(r.vertex_matrix(), r.face_matrix()), test::area(in.V, in.F), 1e-9 * test::area(in.V, in.F));
  for (const auto& p : paths) EXPECT_TRUE(find_halfedge(r.mesh, VertexId(p[0]), VertexId(p[1])).valid());
  expect_exact_provenance(r, input, in.V);
  for (size_t f = 0; f < r.faces.size(); ++f) {
    const auto fv = input.face_vertices(FaceId(r.input_face[f]));
    const Eigen::Vector3d a = in.V.row(fv[0].idx), b = in.V.row(fv[1].idx), c = in.V.row(fv[2].idx);
    const Eigen::Vector3d nrm = (b - a).cross(c - a);
    const Eigen::Vector3d p0 = r.positions[static_cast<size_t>(r.faces[f][0])];
    const Eigen::Vector3d p1 = r.positions[static_cast<size_t>(r.faces[f][1])];
    const Eigen::Vector3d p2 = r.positions[static_cast<size_t>(r.faces[f][2])];
    EXPECT_GT((p1 - p0).cross(p2 - p0).dot(nrm), 0.0) << "face " << f << " flipped or degenerate";
    for (const Eigen::Vector3d& p : {p0, p1, p2}) {
      const double tol = 1e-9 * nrm.squaredNorm();
      EXPECT_GE((b - p).cross(c - p).dot(nrm), -tol) << "face " << f << " leaves its input face";
      EXPECT_GE((c - p).cross(a - p).dot(nrm), -tol) << "face " << f << " leaves its input face";
      EXPECT_GE((a - p).cross(b - p).dot(nrm), -tol) << "face " << f << " leaves its input face";
    }
  }
  // Constrained Delaunay: every edge inside one input face that is not a path segment has opposite angles summing
  // to at most pi.
  std::set<std::pair<int, int>> fixed;
  for (const auto& p : paths) fixed.insert({std::min(p[0], p[1]), std::max(p[0], p[1])});
  for (int e = 0; e < r.mesh.n_edges(); ++e) {
    const HalfedgeId h = Mesh::halfedge(EdgeId(e)), t = Mesh::twin(h);
    const int u = r.mesh.tail(h).idx, w = r.mesh.head(h).idx;
    if (fixed.count({std::min(u, w), std::max(u, w)})) continue;
    const int f1 = r.mesh.face(h).idx, f2 = r.mesh.face(t).idx;
    if (r.input_face[static_cast<size_t>(f1)] != r.input_face[static_cast<size_t>(f2)]) continue;
    const int x = r.mesh.head(r.mesh.next(h)).idx, y = r.mesh.head(r.mesh.next(t)).idx;
    const auto angle = [&](int at, int a, int b) {
      const Eigen::Vector3d p = r.positions[static_cast<size_t>(at)];
      const Eigen::Vector3d da = r.positions[static_cast<size_t>(a)] - p, db = r.positions[static_cast<size_t>(b)] - p;
      return std::atan2(da.cross(db).norm(), da.dot(db));
    };
    EXPECT_LE(angle(x, u, w) + angle(y, w, u), std::numbers::pi * (1 + 1e-6)) << "edge " << u << "-" << w;
  }
}

}  // namespace
}  // namespace liftmap
