#include "lift/lift_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>
#include <tuple>

#include "common/test_meshes.h"
#include "core/errors.h"
#include "lift/local_injectivity.h"
#include "lift_fixtures.h"

namespace liftmap {
namespace {

using Eigen::Vector2d;
using testing::FlatDisk;
using testing::FlatPair;
using K = SurfacePoint::Kind;

struct Meshes {
  explicit Meshes(const FlatPair& p)
      : m(p.m.F, static_cast<int>(p.m.X.rows())), n(p.n.F, static_cast<int>(p.n.X.rows())) {}
  Mesh m;
  Mesh n;
};

double diagonal(const Eigen::MatrixXd& X) { return (X.colwise().maxCoeff() - X.colwise().minCoeff()).norm(); }

/// The invariants of one direction (source -> target): target(map(v)) = source(v), boundary = nu, the round
/// trip through the other direction's point evaluation returns v, no two vertices share an image; and the same
/// at face points.
void check_direction(const Mesh& src, const FlatDisk& s, const Mesh& dst, const FlatDisk& t,
                     const VertexData<SurfacePoint>& map, const std::vector<std::pair<int, int>>& nu,
                     const std::function<SurfacePoint(const SurfacePoint&)>& forward,
                     const std::function<SurfacePoint(const SurfacePoint&)>& back) {
  const double tol_x = 1e-9 * diagonal(s.X);
  const double tol_v = 1e-9 * diagonal(s.V);
  for (int i = 0; i < src.n_vertices(); ++i) {
    const SurfacePoint& y = map[VertexId(i)];
    ASSERT_LE((interpolate(dst, t.X, y) - s.X.row(i)).norm(), tol_x) << "vertex " << i;
    const SurfacePoint x = back(y);
    ASSERT_LE((interpolate(src, s.V, x) - s.V.row(i)).norm(), tol_v) << "round trip of vertex " << i;
    ASSERT_LE((interpolate(src, s.X, x) - s.X.row(i)).norm(), tol_x) << "round trip of vertex " << i;
  }
  for (const auto& [a, b] : nu) {
    ASSERT_EQ(map[VertexId(a)].kind, K::kVertex);
    ASSERT_EQ(map[VertexId(a)].vertex, VertexId(b));
  }
  // No two vertices share an image: same element and same position.
  std::set<std::tuple<int, int, double, double>> seen;
  for (int i = 0; i < src.n_vertices(); ++i) {
    const SurfacePoint& y = map[VertexId(i)];
    const int id = y.kind == K::kVertex ? y.vertex.idx : (y.kind == K::kEdge ? y.edge.idx : y.face.idx);
    ASSERT_TRUE(seen.emplace(static_cast<int>(y.kind), id, s.X(i, 0), s.X(i, 1)).second) << "vertex " << i;
  }
  // Face points (centroids and points near edges and corners), and edge midpoints.
  for (int f = 0; f < src.n_faces(); f += std::max(1, src.n_faces() / 400)) {
    for (const std::array<double, 3>& bary :
         {std::array<double, 3>{1.0 / 3, 1.0 / 3, 1.0 / 3}, std::array<double, 3>{0.5, 0.5 - 1e-15, 1e-15},
          std::array<double, 3>{1 - 2e-13, 1e-13, 1e-13}, std::array<double, 3>{0.25, 0.75, 0.0}}) {
      const SurfacePoint x = SurfacePoint::in_face(FaceId(f), bary);
      const SurfacePoint y = forward(x);
      ASSERT_LE((interpolate(dst, t.X, y) - interpolate(src, s.X, x)).norm(), tol_x) << "face " << f;
      const SurfacePoint x2 = back(y);
      ASSERT_LE((interpolate(src, s.V, x2) - interpolate(src, s.V, x)).norm(), tol_v) << "face " << f;
    }
  }
  for (int e = 0; e < src.n_edges(); e += std::max(1, src.n_edges() / 400)) {
    const SurfacePoint x = SurfacePoint::on_edge(EdgeId(e), 0.375);
    ASSERT_LE((interpolate(dst, t.X, forward(x)) - interpolate(src, s.X, x)).norm(), tol_x) << "edge " << e;
  }
}

/// All invariants of issue 5 on a lifted pair, both directions.
void check_bijection(const FlatPair& p, const Meshes& ms, const LiftedBijection& lift) {
  std::vector<std::pair<int, int>> nu_f;
  std::vector<std::pair<int, int>> nu_g;
  for (Eigen::Index i = 0; i < p.nu.rows(); ++i) {
    nu_f.emplace_back(p.nu(i, 0), p.nu(i, 1));
    nu_g.emplace_back(p.nu(i, 1), p.nu(i, 0));
  }
  auto f = [&](const SurfacePoint& x) { return lift.evaluate_f(x); };
  auto g = [&](const SurfacePoint& y) { return lift.evaluate_g(y); };
  {
    SCOPED_TRACE("f: M -> N");
    check_direction(ms.m, p.m, ms.n, p.n, lift.f(), nu_f, f, g);
  }
  {
    SCOPED_TRACE("g: N -> M");
    check_direction(ms.n, p.n, ms.m, p.m, lift.g(), nu_g, g, f);
  }
}

/// Lifted images equal direct point location Psi^-1(Phi(v)), for pairs where Psi is bijective.
void check_against_point_location(const Mesh& src, const FlatDisk& s, const Mesh& dst, const FlatDisk& t,
                                  const VertexData<SurfacePoint>& map) {
  const testing::PointLocator locator(dst, t.X);
  for (int i = 0; i < src.n_vertices(); ++i) {
    const std::vector<SurfacePoint> found = locator.locate(s.X.row(i).transpose());
    ASSERT_EQ(found.size(), 1u) << "vertex " << i;
    ASSERT_TRUE(testing::same_element(found[0], map[VertexId(i)])) << "vertex " << i;
  }
}

TEST(LiftMap, SameGridWithOtherDiagonalsMapsVerticesToVertices) {
  FlatPair p{testing::grid_disk(5, 5, true), testing::grid_disk(5, 5, false), {}};
  p.nu = testing::match_boundaries(p.m, p.n);
  const Meshes ms(p);
  const LiftedBijection lift(ms.m, p.m.X, ms.n, p.n.X, p.nu);
  for (int i = 0; i < 36; ++i) {
    ASSERT_EQ(lift.f()[VertexId(i)].kind, K::kVertex);
    EXPECT_EQ(lift.f()[VertexId(i)].vertex, VertexId(i));
    EXPECT_EQ(lift.g()[VertexId(i)].vertex, VertexId(i));
  }
  check_bijection(p, ms, lift);
}

// A fan from the centre of an 8 by 8 lattice square to its 32 boundary vertices, against the lattice grid: the
// fan's edges run along grid edges and through grid vertices, grid vertices lie on fan edges. Every image must
// be the exact element that direct point location finds (vertex, edge or face).
TEST(LiftMap, DegenerateFanAgainstLatticeMatchesPointLocation) {
  const int n = 8;
  FlatPair p;
  p.n = testing::grid_disk(n, n, true);
  const Mesh grid(p.n.F, (n + 1) * (n + 1));
  std::vector<int> ring;
  const auto loops = grid.boundary_loops();
  for (const HalfedgeId h : loops.front()) ring.push_back(grid.tail(h).idx);
  p.m.X.resize(static_cast<Eigen::Index>(ring.size()) + 1, 2);
  p.m.X.row(0) << n / 2, n / 2;
  for (size_t k = 0; k < ring.size(); ++k) p.m.X.row(static_cast<Eigen::Index>(k) + 1) = p.n.X.row(ring[k]);
  p.m.F.resize(static_cast<Eigen::Index>(ring.size()), 3);
  for (size_t k = 0; k < ring.size(); ++k) {
    // The boundary loop runs clockwise around the disk; reverse for counter-clockwise faces.
    const int a = static_cast<int>(k) + 1;
    const int b = static_cast<int>((k + 1) % ring.size()) + 1;
    p.m.F.row(static_cast<Eigen::Index>(k)) << 0, b, a;
  }
  p.m.V = Eigen::MatrixXd::Zero(p.m.X.rows(), 3);
  p.m.V.leftCols(2) = p.m.X;
  p.nu = testing::match_boundaries(p.m, p.n);
  const Meshes ms(p);
  ASSERT_TRUE(check_local_injectivity(ms.m, p.m.X).locally_injective());
  const LiftedBijection lift(ms.m, p.m.X, ms.n, p.n.X, p.nu);
  check_against_point_location(ms.m, p.m, ms.n, p.n, lift.f());
  check_against_point_location(ms.n, p.n, ms.m, p.m, lift.g());
  EXPECT_EQ(lift.f()[VertexId(0)].kind, K::kVertex);
  int on_edges = 0;
  for (int i = 0; i < ms.n.n_vertices(); ++i) on_edges += lift.g()[VertexId(i)].kind == K::kEdge;
  EXPECT_GT(on_edges, 8);
  check_bijection(p, ms, lift);
}

// Paper Figure 3: two different triangulations of a strip winding 2.3 times around the origin, with the same
// boundary. Each vertex must land on the right one of up to three preimages: the one at the same parameter.
TEST(LiftMap, OverlappingSpiralsLiftToTheRightSheet) {
  FlatPair p{testing::spiral_strip(6, 160, 2.3, 0.0), testing::spiral_strip(6, 160, 2.3, 0.25), {}};
  p.nu = testing::match_boundaries(p.m, p.n);
  const Meshes ms(p);
  const LiftedBijection lift(ms.m, p.m.X, ms.n, p.n.X, p.nu);
  const testing::PointLocator locator(ms.n, p.n.X);
  int ambiguous = 0;
  for (int i = 0; i < ms.m.n_vertices(); ++i) {
    const Eigen::RowVectorXd param = interpolate(ms.n, p.n.P, lift.f()[VertexId(i)]);
    ASSERT_LT((param - p.m.P.row(i)).norm(), 0.05) << "vertex " << i << " on the wrong sheet";
    ambiguous += locator.locate(p.m.X.row(i).transpose()).size() > 1;
  }
  EXPECT_GT(ambiguous, ms.m.n_vertices() / 2);  // most vertices have several preimages under Psi
  for (int i = 0; i < ms.n.n_vertices(); ++i) {
    const Eigen::RowVectorXd param = interpolate(ms.m, p.m.P, lift.g()[VertexId(i)]);
    ASSERT_LT((param - p.n.P.row(i)).norm(), 0.05) << "vertex " << i << " on the wrong sheet";
  }
  check_bijection(p, ms, lift);
}

TEST(LiftMap, VerificationOffAndOneOffFormGiveTheSameMap) {
  FlatPair p{testing::spiral_strip(5, 121, 1.7, 0.0), testing::spiral_strip(5, 121, 1.7, 0.25), {}};
  p.nu = testing::match_boundaries(p.m, p.n);
  const Meshes ms(p);
  const LiftedBijection checked(ms.m, p.m.X, ms.n, p.n.X, p.nu);
  const LiftedBijection unchecked(ms.m, p.m.X, ms.n, p.n.X, p.nu, {.verify = false});
  const LiftedVertexMaps maps = lift_bijection(ms.m, p.m.X, ms.n, p.n.X, p.nu);
  for (int i = 0; i < ms.m.n_vertices(); ++i) {
    ASSERT_TRUE(testing::same_element(checked.f()[VertexId(i)], unchecked.f()[VertexId(i)]));
    ASSERT_TRUE(testing::same_element(checked.f()[VertexId(i)], maps.f[VertexId(i)]));
  }
  for (int i = 0; i < ms.n.n_vertices(); ++i) {
    ASSERT_TRUE(testing::same_element(checked.g()[VertexId(i)], maps.g[VertexId(i)]));
  }
}

TEST(LiftMap, NotADiskThrows) {
  // A 4 by 4 grid without its 4 middle cells: an annulus.
  FlatPair p{testing::grid_disk(4, 4, true), testing::grid_disk(4, 4, false), {}};
  std::vector<int> keep;
  for (int f = 0; f < 32; ++f) {
    const int cell = f / 2;
    const int i = cell % 4;
    const int j = cell / 4;
    if (!(i >= 1 && i <= 2 && j >= 1 && j <= 2)) keep.push_back(f);
  }
  const Eigen::MatrixXi F = p.m.F(keep, Eigen::all);
  p.nu = testing::match_boundaries(p.m, p.n);
  const Mesh annulus(F, 25);
  const Mesh disk(p.n.F, 25);
  EXPECT_THROW(LiftedBijection(annulus, p.m.X, disk, p.n.X, p.nu), InvalidInputError);
}

TEST(LiftMap, FlippedFaceThrows) {
  FlatPair p{testing::grid_disk(4, 4, true), testing::grid_disk(4, 4, false), {}};
  p.nu = testing::match_boundaries(p.m, p.n);
  p.n.X.row(2 * 5 + 2) << 3.5, 2.2;  // fold: interior vertex pushed over its neighbour
  const Meshes ms(p);
  try {
    const LiftedBijection lift(ms.m, p.m.X, ms.n, p.n.X, p.nu);
    FAIL() << "no exception";
  } catch (const PipelineError& e) {
    EXPECT_NE(std::string(e.what()).find("face"), std::string::npos) << e.what();
  }
}

TEST(LiftMap, BadBoundaryCorrespondenceThrows) {
  FlatPair p{testing::grid_disk(3, 3, true), testing::grid_disk(3, 3, false), {}};
  p.nu = testing::match_boundaries(p.m, p.n);
  const Meshes ms(p);
  Eigen::MatrixXi shifted = p.nu;  // rows rotated: coordinates no longer agree
  for (Eigen::Index i = 0; i < p.nu.rows(); ++i) shifted(i, 1) = p.nu((i + 1) % p.nu.rows(), 1);
  EXPECT_THROW(LiftedBijection(ms.m, p.m.X, ms.n, p.n.X, shifted), InvalidInputError);
  EXPECT_THROW(LiftedBijection(ms.m, p.m.X, ms.n, p.n.X, p.nu.topRows(p.nu.rows() - 1)), InvalidInputError);
  Eigen::MatrixXd moved = p.n.X;
  moved(0, 0) += 1e-12;  // boundary vertex 0 no longer identical
  EXPECT_THROW(LiftedBijection(ms.m, p.m.X, ms.n, moved, p.nu), InvalidInputError);
}

// Issue 5: the lifted map of a Tutte pair equals direct point location Psi_0^-1(Phi_0(x)).
TEST(LiftMap, TuttePairOfCamelAndCowPatchesEqualsPointLocation) {
  const TriangleMesh camel = testing::read_demo_mesh("camel.off");
  const TriangleMesh cow = testing::read_demo_mesh("cow.off");
  const FlatPair p = testing::tutte_pair_of_patches(camel, cow, 2500);
  const Meshes ms(p);
  ASSERT_EQ(ms.m.boundary_loops().size(), 1u);
  const LiftedBijection lift(ms.m, p.m.X, ms.n, p.n.X, p.nu);
  check_against_point_location(ms.m, p.m, ms.n, p.n, lift.f());
  check_against_point_location(ms.n, p.n, ms.m, p.m, lift.g());
  check_bijection(p, ms, lift);
}

/// The same point to the last bit: kind, element and coordinates.
bool identical(const SurfacePoint& a, const SurfacePoint& b) {
  if (a.kind != b.kind) return false;
  switch (a.kind) {
    case K::kVertex:
      return a.vertex == b.vertex;
    case K::kEdge:
      return a.edge == b.edge && a.t == b.t;
    case K::kFace:
      return a.face == b.face && a.bary == b.bary;
  }
  return false;
}

/// Points of every kind on src: its vertices, several points on every edge (both ends, near both ends, inside; two
/// or more per edge, as an overlay has) and face points, in an order that mixes edges.
std::vector<SurfacePoint> mixed_points(const Mesh& src) {
  std::vector<SurfacePoint> pts;
  for (int v = 0; v < src.n_vertices(); v += 3) pts.push_back(SurfacePoint::at_vertex(VertexId(v)));
  for (const double t : {0.375, 0.0, 1e-13, 0.5, 1 - 1e-13, 1.0, 0.8125}) {
    for (int e = src.n_edges() - 1; e >= 0; --e) pts.push_back(SurfacePoint::on_edge(EdgeId(e), t));
  }
  for (int f = 0; f < src.n_faces(); f += 2) {
    pts.push_back(SurfacePoint::in_face(FaceId(f), {0.2, 0.3, 0.5}));
    pts.push_back(SurfacePoint::in_face(FaceId(f), {0.5, 0.5 - 1e-15, 1e-15}));
    pts.push_back(SurfacePoint::in_face(FaceId(f), {0.25, 0.75, 0.0}));
  }
  return pts;
}

// The batch evaluation shares one lift per edge among the points on it; each result must be the single point
// evaluation's, to the last bit, in both directions (the overlay's agreement check relies on it).
TEST(LiftMap, BatchEvaluationEqualsPointByPoint) {
  const TriangleMesh man = testing::read_demo_mesh("man.off");
  const TriangleMesh armadillo = testing::read_demo_mesh("armadillo.off");
  FlatPair p = testing::tutte_pair_of_patches(man, armadillo, 3000);
  testing::exp_warp(p, 3.4);  // overlapping sheets (as in the test below): the batch must find the right one too
  const Meshes ms(p);
  const LiftedBijection lift(ms.m, p.m.X, ms.n, p.n.X, p.nu);
  const std::vector<SurfacePoint> on_m = mixed_points(ms.m);
  const std::vector<SurfacePoint> on_n = mixed_points(ms.n);
  const std::vector<SurfacePoint> f = lift.evaluate_f(on_m);
  const std::vector<SurfacePoint> g = lift.evaluate_g(on_n);
  ASSERT_EQ(f.size(), on_m.size());
  ASSERT_EQ(g.size(), on_n.size());
  for (size_t i = 0; i < on_m.size(); ++i) ASSERT_TRUE(identical(f[i], lift.evaluate_f(on_m[i]))) << "point " << i;
  for (size_t i = 0; i < on_n.size(); ++i) ASSERT_TRUE(identical(g[i], lift.evaluate_g(on_n[i]))) << "point " << i;
  EXPECT_TRUE(lift.evaluate_f(std::vector<SurfacePoint>{}).empty());
}

// Real pair that overlaps itself: the Tutte pair of a man and an armadillo patch warped by z -> exp(3.4 z), which
// winds the disk 1.08 times around the origin (locally injective here, common boundary, liftable through the
// homotopy exp(t z)). The warped lift must stay near the unwarped one (a wrong sheet would be far away).
TEST(LiftMap, WarpedOverlappingTuttePairOfManAndArmadillo) {
  const TriangleMesh man = testing::read_demo_mesh("man.off");
  const TriangleMesh armadillo = testing::read_demo_mesh("armadillo.off");
  const FlatPair flat = testing::tutte_pair_of_patches(man, armadillo, 3000);
  FlatPair p = flat;
  testing::exp_warp(p, 3.4);
  const Meshes ms(p);
  const auto report_m = check_local_injectivity(ms.m, p.m.X);
  const auto report_n = check_local_injectivity(ms.n, p.n.X);
  ASSERT_TRUE(report_m.locally_injective()) << report_m.summary(p.m.X);
  ASSERT_TRUE(report_n.locally_injective()) << report_n.summary(p.n.X);
  const LiftedBijection lift(ms.m, p.m.X, ms.n, p.n.X, p.nu);
  const LiftedBijection flat_lift(ms.m, flat.m.X, ms.n, flat.n.X, flat.nu);
  double max_edge = 0;
  for (int e = 0; e < ms.n.n_edges(); ++e) {
    const HalfedgeId h = Mesh::halfedge(EdgeId(e));
    max_edge = std::max(max_edge, (p.n.V.row(ms.n.tail(h).idx) - p.n.V.row(ms.n.head(h).idx)).norm());
  }
  const testing::PointLocator locator(ms.n, p.n.X);
  int ambiguous = 0;
  for (int i = 0; i < ms.m.n_vertices(); ++i) {
    const auto a = interpolate(ms.n, p.n.V, lift.f()[VertexId(i)]);
    const auto b = interpolate(ms.n, p.n.V, flat_lift.f()[VertexId(i)]);
    ASSERT_LT((a - b).norm(), 3 * max_edge) << "vertex " << i;
    ambiguous += locator.locate(p.m.X.row(i).transpose()).size() > 1;
  }
  EXPECT_GT(ambiguous, 0);  // the warped flattening does overlap itself
  check_bijection(p, ms, lift);
}

}  // namespace
}  // namespace liftmap
