#include "cut/cut_meshes.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <set>

#include "core/errors.h"
#include "core/thread_count_scope.h"
#include "cut_test_util.h"

namespace liftmap {
namespace {

using test::Pattern;

using test::Case;
using test::run;

TEST(cut_meshes, TwoLandmarks) { run({"cow", "triceratops"}, 2, Pattern::kRandom, 1); }

TEST(cut_meshes, RandomLandmarksOnSeveralPairs) {
  const Case cases[] = {{"cow", "triceratops"}, {"hand", "blobby"}, {"bull", "dino"}, {"homer", "camel"}};
  unsigned seed = 10;
  for (const Case& c : cases) {
    for (const int k : {3, 8, 20}) run(c, k, Pattern::kRandom, seed++);
  }
}

TEST(cut_meshes, CloseTogetherLandmarks) {
  unsigned seed = 100;
  for (const int k : {3, 6, 12, 20}) run({"cow", "hand"}, k, Pattern::kClose, seed++);
}

TEST(cut_meshes, NearlyCollinearLandmarks) {
  unsigned seed = 200;
  for (const int k : {3, 6, 12, 20}) run({"triceratops", "blobby"}, k, Pattern::kCollinear, seed++);
}

TEST(cut_meshes, MixedPatternsBetweenMeshes) {
  // Clustered on one mesh, spread on the other: the geodesic trees disagree and need sector repair.
  const auto ma = test::load("cow"), mb = test::load("bull");
  for (unsigned seed = 300; seed < 304; ++seed) {
    std::mt19937 rng(seed);
    const auto la = test::landmark_set(ma, 15, Pattern::kClose, rng);
    const auto lb = test::landmark_set(mb, 15, Pattern::kRandom, rng);
    const CutResult r = cut_meshes(ma.V, ma.F, mb.V, mb.F, la, lb);
    test::check_cut(r, ma, mb, la, lb);
  }
}

TEST(cut_meshes, TheSameCutOnOneThreadAndOnTwo) {
  // The two meshes' steps run on a thread each where two are available, the landmark distances on all: the cut
  // must not depend on the thread count, to the last bit.
  const auto ma = test::load("homer"), mb = test::load("camel");
  std::mt19937 rng(5);
  const auto la = test::landmark_set(ma, 8, Pattern::kRandom, rng);
  const auto lb = test::landmark_set(mb, 8, Pattern::kRandom, rng);
  const auto cut_on = [&](int threads) {
    const ThreadCountScope scope(threads);
    return cut_meshes(ma.V, ma.F, mb.V, mb.F, la, lb);
  };
  const CutResult one = cut_on(1), two = cut_on(2);
  EXPECT_EQ(one.tree, two.tree);
  EXPECT_EQ(one.nu, two.nu);
  for (const auto& [x, y] : {std::pair{&one.a, &two.a}, std::pair{&one.b, &two.b}}) {
    EXPECT_TRUE(x->V == y->V);
    EXPECT_TRUE(x->F == y->F);
    EXPECT_TRUE(x->F_cut == y->F_cut);
    EXPECT_TRUE(x->cut_to_refined == y->cut_to_refined);
    EXPECT_EQ(x->landmarks, y->landmarks);
    EXPECT_EQ(x->paths, y->paths);
    EXPECT_EQ(x->path_lengths, y->path_lengths);
  }
}

TEST(cut_meshes, AFaceThatCannotBeRetriangulatedKeepsTheTracedTriangulation) {
  // The cut sweep's configuration in which tracing left two refined vertices at one point of an input face: the
  // constrained Delaunay re-triangulation cannot take it, and the cut goes on with the traced triangulation.
  run({"triceratops", "cow"}, 16, Pattern::kClose, 1349420280);
}

/// k landmarks anywhere on a mesh, seeded: points inside random faces (the first two in one face), on edges (a
/// zero coordinate) and at vertices, as a landmark file gives them (face points in the order of F's rows).
std::vector<SurfacePoint> surface_landmarks(const TriangleMesh& m, int k, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.05, 0.9);
  std::set<int> faces;
  std::vector<SurfacePoint> out;
  int f = static_cast<int>(rng() % static_cast<unsigned>(m.F.rows()));
  for (int i = 0; i < k; ++i) {
    if (i > 1) {
      do {
        f = static_cast<int>(rng() % static_cast<unsigned>(m.F.rows()));
      } while (faces.count(f));
    }
    faces.insert(f);
    const double a = u(rng), b = u(rng) * (1 - a);
    std::array<double, 3> w{a, b, 1 - a - b};
    if (i % 4 == 2) w = {a, 1 - a, 0};  // on an edge
    if (i % 4 == 3) {                   // at a vertex
      out.push_back(SurfacePoint::at_vertex(VertexId(m.F(f, 0))));
      continue;
    }
    out.push_back(SurfacePoint::in_face(FaceId(f), w));
  }
  return out;
}

// A path that passes a landmark or another path keeps clear of it by at least 5% of its input face's shortest edge.
// The clearance used to be 5% of the edge left by the previous straightening step, which compounded: on cow to
// triceratops with these 12 landmarks three paths passed landmark 1 (vertex 273 of the cow) 1e-12 away, the disk
// had faces of 1e-22 of the mean area, and the map failed (the Newton step of its first subproblem was not finite).
TEST(cut_meshes, PathsKeepClearOfBlockedVertices) {
  const auto ma = test::load("cow"), mb = test::load("triceratops");
  const int pairs[12][2] = {{525, 1185},  {273, 1657}, {685, 2705}, {114, 1881}, {2519, 488}, {2347, 1457},
                            {1257, 2224}, {964, 1215}, {247, 804},  {519, 2085}, {2322, 906}, {1688, 2140}};
  std::vector<VertexId> la, lb;
  for (const auto& p : pairs) {
    la.emplace_back(p[0]);
    lb.emplace_back(p[1]);
  }
  const CutResult r = cut_meshes(ma.V, ma.F, mb.V, mb.F, la, lb);
  test::check_cut(r, ma, mb, la, lb);
  const auto shortest_edge = [](const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
    double l = std::numeric_limits<double>::infinity();
    for (int f = 0; f < F.rows(); ++f) {
      for (int k = 0; k < 3; ++k) l = std::min(l, (V.row(F(f, k)) - V.row(F(f, (k + 1) % 3))).norm());
    }
    return l;
  };
  // Against the input's shortest edge: 6e-11 before the floor, 7e-4 with a floor of 1% (the pairing of the two sides'
  // path vertices and the crossings near input vertices place points nearer each other than the clearance).
  EXPECT_GT(shortest_edge(r.a.V, r.a.F), 1e-4 * shortest_edge(ma.V, ma.F));
  EXPECT_GT(shortest_edge(r.b.V, r.b.F), 1e-4 * shortest_edge(mb.V, mb.F));
}

TEST(cut_meshes, SurfacePointLandmarksBecomeVerticesAtTheirPoints) {
  const Case cases[] = {{"cow", "triceratops"}, {"hand", "blobby"}, {"bull", "dino"}};
  unsigned seed = 500;
  for (const Case& c : cases) {
    const auto ma = test::load(c.a), mb = test::load(c.b);
    for (const int k : {2, 5, 12}) {
      SCOPED_TRACE(std::string(c.a) + "-" + c.b + " k=" + std::to_string(k) + " seed=" + std::to_string(seed));
      std::mt19937 rng(seed++);
      const auto la = surface_landmarks(ma, k, rng);
      const auto lb = surface_landmarks(mb, k, rng);
      const CutResult r = cut_meshes(ma.V, ma.F, mb.V, mb.F, la, lb);
      test::check_cut(r, ma, mb, la, lb);
    }
  }
}

TEST(cut_meshes, RejectsSurfaceLandmarksAtOnePoint) {
  const auto m = test::load("cow");
  const std::vector<SurfacePoint> ok{SurfacePoint::at_vertex(VertexId(0)), SurfacePoint::at_vertex(VertexId(1))};
  // A face point with one positive coordinate is its corner: the vertex landmark 0 again.
  const int corner = m.F(7, 1);
  const std::vector<SurfacePoint> same_vertex{SurfacePoint::at_vertex(VertexId(corner)),
                                              SurfacePoint::in_face(FaceId(7), {0, 1, 0})};
  EXPECT_THROW(cut_meshes(m.V, m.F, m.V, m.F, same_vertex, ok), InvalidInputError);
  const std::vector<SurfacePoint> same_face_point{SurfacePoint::in_face(FaceId(7), {0.2, 0.3, 0.5}),
                                                  SurfacePoint::in_face(FaceId(7), {0.2, 0.3, 0.5})};
  EXPECT_THROW(cut_meshes(m.V, m.F, m.V, m.F, ok, same_face_point), InvalidInputError);
  const std::vector<SurfacePoint> bad_face{SurfacePoint::at_vertex(VertexId(0)),
                                           SurfacePoint::in_face(FaceId(static_cast<int>(m.F.rows())), {1, 0, 0})};
  EXPECT_THROW(cut_meshes(m.V, m.F, m.V, m.F, bad_face, ok), InvalidInputError);
}

TEST(cut_meshes, PathTreeOption) {
  CutOptions options;
  options.tree = CutOptions::Tree::kPath;
  run({"cow", "triceratops"}, 10, Pattern::kRandom, 400, options);
}

TEST(cut_meshes, WithoutShortening) {
  CutOptions options;
  options.geodesic_paths = false;
  run({"hand", "cow"}, 10, Pattern::kRandom, 500, options);
}

TEST(cut_meshes, TwoLandmarksOnOneVertexIsAnInputError) {
  const auto m = test::load("cow");
  const std::vector<VertexId> la{VertexId(1), VertexId(5), VertexId(1)};
  const std::vector<VertexId> lb{VertexId(1), VertexId(2), VertexId(3)};
  try {
    (void)cut_meshes(m.V, m.F, m.V, m.F, la, lb);
    FAIL() << "expected InvalidInputError";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("same vertex 1"), std::string::npos) << e.what();
  }
}

TEST(cut_meshes, OtherInputErrors) {
  const auto m = test::load("cow");
  const std::vector<VertexId> two{VertexId(1), VertexId(2)};
  const std::vector<VertexId> three{VertexId(1), VertexId(2), VertexId(3)};
  EXPECT_THROW((void)cut_meshes(m.V, m.F, m.V, m.F, two, three), InvalidInputError);
  EXPECT_THROW((void)cut_meshes(m.V, m.F, m.V, m.F, {VertexId(1)}, {VertexId(1)}), InvalidInputError);
  EXPECT_THROW((void)cut_meshes(m.V, m.F, m.V, m.F, two, {VertexId(1), VertexId(1 << 30)}), InvalidInputError);
  // An open mesh is not a valid input.
  const Eigen::MatrixXi open = m.F.topRows(m.F.rows() - 1);
  EXPECT_THROW((void)cut_meshes(m.V, open, m.V, m.F, two, two), InvalidInputError);
}

}  // namespace
}  // namespace liftmap
