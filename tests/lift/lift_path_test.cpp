#include "lift/lift_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/errors.h"
#include "lift_fixtures.h"

namespace liftmap {
namespace {

using Eigen::Vector2d;
using testing::FlatDisk;
using K = SurfacePoint::Kind;

constexpr int kN = 6;  // 6 by 6 grid of "/" cells on integer coordinates
int vid(int i, int j) { return j * (kN + 1) + i; }

class LiftGridWalk : public ::testing::Test {
 protected:
  LiftGridWalk()
      : disk_(testing::grid_disk(kN, kN, true)), mesh_(disk_.F, (kN + 1) * (kN + 1)), lifter_(mesh_, disk_.X) {}

  EdgeId edge(int a, int b) const {
    EdgeId e;
    mesh_.for_each_outgoing(VertexId(a), [&](HalfedgeId h) {
      if (mesh_.head(h) == VertexId(b)) e = Mesh::edge(h);
    });
    return e;
  }
  Vector2d at(const SurfacePoint& p) const { return interpolate(mesh_, disk_.X, p).transpose(); }

  /// Lifts [a, b] from `start` and checks the trace: nodes on the segment in order, faces holding the pieces.
  SurfacePoint walk(const SurfacePoint& start, const Vector2d& a, const Vector2d& b) const {
    LiftTrace trace;
    const SurfacePoint end = lifter_.lift_segment(start, a, b, &trace);
    EXPECT_EQ(trace.nodes.size(), trace.s.size());
    EXPECT_EQ(trace.faces.size() + 1, trace.nodes.size());
    for (size_t k = 0; k < trace.nodes.size(); ++k) {
      const Vector2d p = at(trace.nodes[k]);
      EXPECT_LT((p - (a + trace.s[k] * (b - a))).norm(), 1e-12) << "node " << k;
      if (k > 0) {
        EXPECT_GE(trace.s[k], trace.s[k - 1]);
      }
    }
    EXPECT_LT((at(end) - b).norm(), 1e-12);
    return end;
  }

  FlatDisk disk_;
  Mesh mesh_;
  PathLifter lifter_;
};

TEST_F(LiftGridWalk, AlongEdgesThroughVertices) {
  // Along the "/" diagonals from corner to corner: every step runs along an edge, through vertices.
  const SurfacePoint end = walk(SurfacePoint::at_vertex(VertexId(0)), {0, 0}, {4, 4});
  ASSERT_EQ(end.kind, K::kVertex);
  EXPECT_EQ(end.vertex, VertexId(vid(4, 4)));
  // Along the boundary.
  const SurfacePoint b = walk(SurfacePoint::at_vertex(VertexId(0)), {0, 0}, {0, 5});
  ASSERT_EQ(b.kind, K::kVertex);
  EXPECT_EQ(b.vertex, VertexId(vid(0, 5)));
}

TEST_F(LiftGridWalk, ThroughVerticesAcrossFaces) {
  // Slope 1/2 passes exactly through vertices (2, 1) and (4, 2), crossing faces in between.
  LiftTrace trace;
  const SurfacePoint end = lifter_.lift_segment(SurfacePoint::at_vertex(VertexId(0)), {0, 0}, {5, 2.5}, &trace);
  int vertices_passed = 0;
  for (const SurfacePoint& p : trace.nodes) vertices_passed += p.kind == K::kVertex;
  EXPECT_EQ(vertices_passed, 3);  // start, (2, 1), (4, 2)
  ASSERT_EQ(end.kind, K::kEdge);  // (5, 2.5) is the midpoint of the vertical edge (5, 2)-(5, 3)
  EXPECT_EQ(end.edge, edge(vid(5, 2), vid(5, 3)));
  walk(SurfacePoint::at_vertex(VertexId(0)), {0, 0}, {5, 2.5});
}

TEST_F(LiftGridWalk, StartingOnAnEdge) {
  const EdgeId e = edge(vid(1, 0), vid(1, 1));
  const SurfacePoint start = SurfacePoint::on_edge(e, 0.5);
  // Across: horizontal at y = 0.5 through diagonals and verticals, ending inside a face.
  SurfacePoint end = walk(start, {1, 0.5}, {3.25, 0.5});
  ASSERT_EQ(end.kind, K::kFace);
  // Along the edge, through vertices (1, 1) and (1, 2), to vertex (1, 3).
  end = walk(start, {1, 0.5}, {1, 3});
  ASSERT_EQ(end.kind, K::kVertex);
  EXPECT_EQ(end.vertex, VertexId(vid(1, 3)));
  // Along the edge and ending on it, both directions.
  end = walk(start, {1, 0.5}, {1, 0.75});
  ASSERT_EQ(end.kind, K::kEdge);
  EXPECT_EQ(end.edge, e);
  end = walk(start, {1, 0.5}, {1, 0.25});
  ASSERT_EQ(end.kind, K::kEdge);
  EXPECT_EQ(end.edge, e);
  // To the left, ending exactly on a diagonal edge.
  end = walk(start, {1, 0.5}, {0.5, 0.5});
  ASSERT_EQ(end.kind, K::kEdge);
  EXPECT_EQ(end.edge, edge(vid(0, 0), vid(1, 1)));
  // A face start whose point lies on an edge is refined to that edge.
  const SurfacePoint refined = lifter_.refine(SurfacePoint::in_face(FaceId(0), {1, 0, 0}), {1, 0.5});
  ASSERT_EQ(refined.kind, K::kEdge);
  EXPECT_EQ(refined.edge, e);
}

TEST_F(LiftGridWalk, FromAFaceToAVertex) {
  const SurfacePoint start = SurfacePoint::in_face(FaceId(0), {0.5, 0.25, 0.25});
  const Vector2d a = at(start);
  const SurfacePoint end = walk(start, a, {3, 5});
  ASSERT_EQ(end.kind, K::kVertex);
  EXPECT_EQ(end.vertex, VertexId(vid(3, 5)));
}

TEST_F(LiftGridWalk, LeavingTheDiskThrows) {
  // Through a boundary edge, through a boundary vertex, and from a boundary edge straight out.
  EXPECT_THROW(lifter_.lift_segment(SurfacePoint::at_vertex(VertexId(vid(1, 1))), {1, 1}, {10, 1.5}), PipelineError);
  EXPECT_THROW(lifter_.lift_segment(SurfacePoint::at_vertex(VertexId(vid(1, 1))), {1, 1}, {-1, -1}), PipelineError);
  EXPECT_THROW(lifter_.lift_segment(SurfacePoint::at_vertex(VertexId(0)), {0, 0}, {-1, 0.5}), PipelineError);
  const EdgeId boundary = edge(vid(0, 2), vid(0, 3));
  EXPECT_THROW(lifter_.lift_segment(SurfacePoint::on_edge(boundary, 0.5), {0, 2.5}, {-0.5, 2.5}), PipelineError);
  try {
    lifter_.lift_segment(SurfacePoint::at_vertex(VertexId(vid(1, 1))), {1, 1}, {10, 1.5});
  } catch (const PipelineError& e) {
    EXPECT_NE(std::string(e.what()).find("boundary edge"), std::string::npos) << e.what();
  }
}

TEST_F(LiftGridWalk, StartNotContainingThePointThrows) {
  EXPECT_THROW(lifter_.lift_segment(SurfacePoint::at_vertex(VertexId(0)), {0.5, 0}, {1, 1}), InvalidInputError);
  EXPECT_THROW(lifter_.lift_segment(SurfacePoint::in_face(FaceId(0), {1, 0, 0}), {3, 3}, {1, 1}), InvalidInputError);
}

TEST_F(LiftGridWalk, PolylineLift) {
  Eigen::MatrixXd W(4, 2);
  W << 0.25, 0.5, 3, 3, 3, 0.5, 5.5, 5.5;
  const SurfacePoint start = lifter_.refine(SurfacePoint::in_face(FaceId(1), {1.0 / 3, 1.0 / 3, 1.0 / 3}), {0.25, 0.5});
  const LiftedPath path = lift_path(mesh_, disk_.X, start, W);
  ASSERT_EQ(path.row_index.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    EXPECT_LT(
        (at(path.points[static_cast<size_t>(path.row_index[static_cast<size_t>(i)])]) - W.row(i).transpose()).norm(),
        1e-12);
  }
  EXPECT_EQ(path.points[static_cast<size_t>(path.row_index[1])].kind, K::kVertex);
  EXPECT_EQ(path.points[static_cast<size_t>(path.row_index[3])].kind, K::kEdge);  // (5.5, 5.5) on a diagonal
}

TEST(LiftPath, NotLocallyInjectiveThrows) {
  FlatDisk grid = testing::grid_disk(4, 4, true);
  grid.X.row(2 * 5 + 2) << 3.5, 2.2;
  EXPECT_THROW(PathLifter(Mesh(grid.F, 25), grid.X), PipelineError);
}

// A point that rounding put just outside a sliver goes to the nearest point of the edge it fell across. Clamping
// its negative coordinate to 0 and renormalising moved it along the sliver by its length times the overshoot over
// the sliver's height: here 2e-4 for an overshoot of 1e-12 (on real maps, 8e-12 of the mesh, enough to fail the
// overlay check).
TEST(LiftPath, FacePointOutsideASliverGoesToTheNearestEdgePoint) {
  Eigen::MatrixXd X(3, 2);
  X << 0, 0, 1, 0, 0.5, 1e-9;
  const Eigen::MatrixXi F = (Eigen::MatrixXi(1, 3) << 0, 1, 2).finished();
  const Mesh mesh(F, 3);
  const PathLifter lifter(mesh, X);
  for (const double below : {1e-15, 1e-12, 1e-10}) {
    const Vector2d z(0.3, -below);
    const SurfacePoint p = lifter.face_point(FaceId(0), z);
    EXPECT_LT((interpolate(mesh, X, p).transpose() - Vector2d(0.3, 0)).norm(), 1e-15) << "overshoot " << below;
    const SurfacePoint q = lifter.refine_coordinates(p, 0.3L, -static_cast<long double>(below));
    EXPECT_LT((interpolate(mesh, X, q).transpose() - Vector2d(0.3, 0)).norm(), 1e-15) << "overshoot " << below;
  }
  // Inside, the coordinates are the barycentric ones.
  const SurfacePoint inside = lifter.face_point(FaceId(0), Vector2d(0.5, 0.5e-9));
  EXPECT_LT((interpolate(mesh, X, inside).transpose() - Vector2d(0.5, 0.5e-9)).norm(), 1e-16);
}

// Paper Figure 3: a spiral strip winding 2.3 times around the origin. A polyline following the middle circle of
// the strip lifts onto the right sheet, although its end point has three preimages under Psi.
TEST(LiftPath, OverlappingSpiralStaysOnItsSheet) {
  const double turns = 2.3;
  const FlatDisk d = testing::spiral_strip(5, 200, turns, 0.3);
  const Mesh mesh(d.F, static_cast<int>(d.X.rows()));
  const PathLifter lifter(mesh, d.X);
  const double total = turns * 2 * std::numbers::pi;
  const int n = 400;
  Eigen::MatrixXd W(n + 1, 2);
  for (int k = 0; k <= n; ++k) {
    const double theta = (total - 0.05) * k / n;
    W.row(k) << 1.5 * std::cos(theta), 1.5 * std::sin(theta);
  }
  // Vertex (2, 0) of the strip is at r = 1.5, theta = 0 (a boundary vertex, as where f is known).
  ASSERT_EQ(d.X.row(2), W.row(0));
  const LiftedPath path = lifter.lift_polyline(SurfacePoint::at_vertex(VertexId(2)), W);
  for (int k = 0; k <= n; ++k) {
    const SurfacePoint& p = path.points[static_cast<size_t>(path.row_index[static_cast<size_t>(k)])];
    const Eigen::RowVectorXd param = interpolate(mesh, d.P, p);
    const double theta = (total - 0.05) * k / n;
    ASSERT_NEAR(param(1), theta, 0.1) << "polyline point " << k << " lifted to the wrong sheet";
    ASSERT_LT((interpolate(mesh, d.X, p) - W.row(k)).norm(), 1e-12);
  }
  // The end point has 3 preimages under Psi: the lift picked one of several.
  const testing::PointLocator locator(mesh, d.X);
  EXPECT_GE(locator.locate(W.row(n).transpose()).size(), 3u);
}

}  // namespace
}  // namespace liftmap
