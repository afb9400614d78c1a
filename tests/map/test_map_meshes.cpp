#include "map/map_meshes.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <random>
#include <set>
#include <sstream>

#include "common/test_meshes.h"
#include "core/errors.h"
#include "io/landmarks.h"
#include "map/check_overlay.h"
#include "map/write_map.h"

namespace liftmap {
namespace {

std::vector<VertexId> random_vertices(int n_vertices, int k, std::mt19937& rng) {
  std::set<int> chosen;
  while (static_cast<int>(chosen.size()) < k)
    chosen.insert(static_cast<int>(rng() % static_cast<unsigned>(n_vertices)));
  std::vector<VertexId> out;
  for (int v : chosen) out.emplace_back(v);
  std::shuffle(out.begin(), out.end(), rng);
  return out;
}

using testing::position;
using testing::sqrt_area;

// The end-to-end invariants of the map on a real pair with seeded random landmarks.
void expect_valid_map(const TriangleMesh& A, const TriangleMesh& B, int k, unsigned seed, MapOptions options = {}) {
  std::mt19937 rng(seed);
  const auto la = random_vertices(static_cast<int>(A.V.rows()), k, rng);
  const auto lb = random_vertices(static_cast<int>(B.V.rows()), k, rng);
  options.flatten.max_iterations = 3;  // the invariants hold after any number of outer iterations
  const MapResult map = map_meshes(A.V, A.F, B.V, B.F, la, lb, options);
  const MapVerification& v = map.verification;
  EXPECT_TRUE(v.passed) << (v.failures.empty() ? "" : v.failures.front());
  EXPECT_GT(v.min_orientation, 0.0);
  EXPECT_LT(v.max_boundary_angle_sum, 2 * M_PI);
  EXPECT_LT(v.lifting_residual, 1e-9);
  EXPECT_LT(v.round_trip_error, 1e-9);

  // Landmarks map exactly onto their partners, both ways.
  for (int i = 0; i < k; ++i) {
    EXPECT_LT((position(B, map.a_to_b[static_cast<size_t>(la[i].idx)]) - B.V.row(lb[i].idx).transpose()).norm(),
              1e-12 * sqrt_area(B));
    EXPECT_LT((position(A, map.b_to_a[static_cast<size_t>(lb[i].idx)]) - A.V.row(la[i].idx).transpose()).norm(),
              1e-12 * sqrt_area(A));
  }
  // No two vertices share an image (injectivity on vertices).
  std::vector<std::array<double, 3>> images;
  for (const auto& p : map.a_to_b) {
    const Eigen::Vector3d x = position(B, p);
    images.push_back({x.x(), x.y(), x.z()});
  }
  std::sort(images.begin(), images.end());
  EXPECT_EQ(std::adjacent_find(images.begin(), images.end()), images.end());

  // g(f(x)) = x at random points inside faces of A, through the input-mesh evaluator.
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst = 0;
  for (int i = 0; i < 300; ++i) {
    const int f = static_cast<int>(rng() % static_cast<unsigned>(A.F.rows()));
    const double a = u(rng), b = u(rng) * (1 - a);
    const SurfacePoint x = SurfacePoint::in_face(FaceId(f), {a, b, 1 - a - b});
    const SurfacePoint y = evaluate_map(map, Side::kA, x);
    const SurfacePoint back = evaluate_map(map, Side::kB, y);
    worst = std::max(worst, (position(A, back) - position(A, x)).norm() / sqrt_area(A));
  }
  EXPECT_LT(worst, 1e-9);
  // Every overlay triangle knows how precisely its sign is known on each side: never below the input faces' own
  // rounding, and on these well-shaped flattenings nowhere near a visible area (a tolerance that hid folds).
  const Overlay& o = map.overlay;
  ASSERT_GT(o.F.rows(), 0);
  ASSERT_EQ(o.rounding_a.size(), o.F.rows());
  ASSERT_EQ(o.rounding_b.size(), o.F.rows());
  EXPECT_GE(std::min(o.rounding_a.minCoeff(), o.rounding_b.minCoeff()), OverlayCheck::kRoundingArea);
  EXPECT_LT(std::max(o.rounding_a.maxCoeff(), o.rounding_b.maxCoeff()), 1e-8);
  // The distortion of f is finite and at least 1 (max(Sigma, 1/sigma) >= 1).
  EXPECT_GE(map.distortion_f.mean, 1.0);
  EXPECT_TRUE(std::isfinite(map.distortion_f.max));
}

TEST(MapMeshes, SpheresWithRandomLandmarks) {
  const TriangleMesh sphere = testing::read_demo_mesh("larger_sphere.off");
  const TriangleMesh ellipsoid = testing::read_demo_mesh("ellipsoid.off");
  for (int k : {3, 6}) {
    SCOPED_TRACE("k = " + std::to_string(k));
    expect_valid_map(sphere, ellipsoid, k, 100 + static_cast<unsigned>(k));
  }
}

// p = inf, which the default solver choice hands to the primal-dual method; and p = 2 forced onto it.
TEST(MapMeshes, SpheresWithThePrimalDualSolver) {
  const TriangleMesh sphere = testing::read_demo_mesh("larger_sphere.off");
  const TriangleMesh ellipsoid = testing::read_demo_mesh("ellipsoid.off");
  MapOptions inf;
  inf.flatten.p = std::numeric_limits<double>::infinity();
  expect_valid_map(sphere, ellipsoid, 6, 106, inf);
  MapOptions two;
  two.flatten.method = SubproblemSolver::kPrimalDual;
  expect_valid_map(sphere, ellipsoid, 6, 106, two);
}

// Landmarks given as face points, points on edges and 3D points (through the landmark file's reader) map exactly
// onto their partners: each is a vertex of the refined mesh at exactly its point.
TEST(MapMeshes, SurfacePointLandmarksMapExactly) {
  const TriangleMesh sphere = testing::read_demo_mesh("larger_sphere.off");
  const TriangleMesh ellipsoid = testing::read_demo_mesh("ellipsoid.off");
  // The axis extremes of examples/sphere-ellipsoid, moved off the vertices into a face around each.
  const Mesh mesh_a(sphere.F, static_cast<int>(sphere.V.rows()));
  const Mesh mesh_b(ellipsoid.F, static_cast<int>(ellipsoid.V.rows()));
  const auto face_at = [](const Mesh& m, int v) { return m.face(m.halfedge(VertexId(v))).idx; };
  const auto point_3d = [](const TriangleMesh& m, int f, const std::array<double, 3>& b) {
    const Eigen::Vector3d x = position(m, SurfacePoint::in_face(FaceId(f), b));
    char s[128];
    std::snprintf(s, sizeof s, "%.17g,%.17g,%.17g", x.x(), x.y(), x.z());
    return std::string(s);
  };
  const int pairs[6][2] = {{286, 117}, {276, 138}, {294, 0}, {314, 11}, {304, 70}, {280, 46}};
  std::ostringstream file;
  file << pairs[0][0] << " " << pairs[0][1] << "\n";  // vertices
  for (int i = 1; i < 6; ++i) {
    const int fa = face_at(mesh_a, pairs[i][0]), fb = face_at(mesh_b, pairs[i][1]);
    if (i % 2 == 1) {  // a face point of A, a 3D point on B
      file << "f" << fa << ":0.5,0.3,0.2 " << point_3d(ellipsoid, fb, {0.25, 0.25, 0.5}) << "\n";
    } else {  // a point on an edge of A, a face point of B
      file << "f" << fa << ":0.6,0,0.4 f" << fb << ":0.1,0.2,0.7\n";
    }
  }
  std::istringstream in(file.str());
  const Landmarks lm = read_landmarks(in, "surface.txt", sphere.V, sphere.F, ellipsoid.V, ellipsoid.F);
  EXPECT_TRUE(lm.warnings.empty());
  MapOptions options;
  options.flatten.max_iterations = 3;
  const MapResult map = map_meshes(sphere.V, sphere.F, ellipsoid.V, ellipsoid.F, lm.a, lm.b, options);
  const MapVerification& v = map.verification;
  EXPECT_TRUE(v.passed) << (v.failures.empty() ? "" : v.failures.front());
  EXPECT_LE(v.landmark_error, 1e-12);
  const double diag_a = (sphere.V.colwise().maxCoeff() - sphere.V.colwise().minCoeff()).norm();
  const double diag_b = (ellipsoid.V.colwise().maxCoeff() - ellipsoid.V.colwise().minCoeff()).norm();
  for (size_t i = 0; i < lm.a.size(); ++i) {
    const Eigen::Vector3d pa = interpolate(mesh_a, sphere.V, lm.a[i]).transpose();
    const Eigen::Vector3d pb = interpolate(mesh_b, ellipsoid.V, lm.b[i]).transpose();
    // The inserted vertex is the requested point.
    EXPECT_LT((map.cut.a.V.row(map.cut.a.landmarks[i]).transpose() - pa).norm(), 1e-12 * diag_a) << i;
    EXPECT_LT((map.cut.b.V.row(map.cut.b.landmarks[i]).transpose() - pb).norm(), 1e-12 * diag_b) << i;
    // f and g take it onto its partner.
    const SurfacePoint fa = evaluate_map(map, Side::kA, lm.a[i]);
    const SurfacePoint gb = evaluate_map(map, Side::kB, lm.b[i]);
    EXPECT_LT((position(ellipsoid, fa) - pb).norm(), 1e-12 * sqrt_area(ellipsoid)) << i;
    EXPECT_LT((position(sphere, gb) - pa).norm(), 1e-12 * sqrt_area(sphere)) << i;
  }
  EXPECT_EQ(lm.b[1].kind, SurfacePoint::Kind::kFace);  // the 3D point, located in its face
}

TEST(MapMeshes, MapFilesRoundTrip) {
  const TriangleMesh sphere = testing::read_demo_mesh("geosphere.off");
  const TriangleMesh ellipsoid = testing::read_demo_mesh("ellipsoid.off");
  std::mt19937 rng(5);
  const auto la = random_vertices(static_cast<int>(sphere.V.rows()), 4, rng);
  const auto lb = random_vertices(static_cast<int>(ellipsoid.V.rows()), 4, rng);
  MapOptions options;
  options.flatten.max_iterations = 2;
  const MapResult map = map_meshes(sphere.V, sphere.F, ellipsoid.V, ellipsoid.F, la, lb, options);
  ASSERT_TRUE(map.verification.passed);
  const std::string path = (std::filesystem::temp_directory_path() / "liftmap_test_A_to_B.txt").string();
  write_vertex_map(path, map.a_to_b, "test");
  const auto back = read_vertex_map(path, static_cast<int>(ellipsoid.F.rows()));
  ASSERT_EQ(back.size(), map.a_to_b.size());
  for (size_t i = 0; i < back.size(); ++i) {
    EXPECT_EQ(back[i].face, map.a_to_b[i].face);
    EXPECT_EQ(back[i].bary, map.a_to_b[i].bary) << "17 digits must round-trip";
  }
  EXPECT_THROW(read_vertex_map(path, 3), IoError);
  std::filesystem::remove(path);
}

TEST(MapMeshes, RejectsInvalidInput) {
  const TriangleMesh cow = testing::read_demo_mesh("cow.off");
  const TriangleMesh elephant = testing::read_demo_mesh("elephant.off");
  const std::vector<VertexId> l{VertexId(0), VertexId(1)};
  EXPECT_THROW(map_meshes(cow.V, cow.F, elephant.V, elephant.F, l, l), InvalidInputError);
  EXPECT_THROW(map_meshes(cow.V, cow.F, cow.V, cow.F, {VertexId(0)}, {VertexId(0)}), InvalidInputError);
  const auto message = [&](const std::vector<SurfacePoint>& a, const std::vector<SurfacePoint>& b,
                           const MapOptions& options) -> std::string {
    try {
      (void)map_meshes(cow.V, cow.F, cow.V, cow.F, a, b, options);
    } catch (const InvalidInputError& e) {
      return e.what();
    }
    return "accepted";
  };
  // Landmarks from a C++ caller pass the landmark files' rule: two face points 1e-10 of a face apart cannot be cut
  // apart (in a map they ended in a degenerate face of the cut disk).
  const std::vector<SurfacePoint> a{SurfacePoint::at_vertex(VertexId(0)),
                                    SurfacePoint::in_face(FaceId(100), {0.2, 0.3, 0.5}),
                                    SurfacePoint::in_face(FaceId(100), {0.2, 0.3 + 1e-10, 0.5 - 1e-10})};
  const std::vector<SurfacePoint> b{SurfacePoint::at_vertex(VertexId(0)), SurfacePoint::at_vertex(VertexId(1)),
                                    SurfacePoint::at_vertex(VertexId(2))};
  MapOptions options;
  options.name_a = "cow A";
  EXPECT_NE(message(a, b, options).find("map: cow A: landmarks 1 and 2 are"), std::string::npos)
      << message(a, b, options);
  EXPECT_NE(message(a, b, options).find("too close to cut apart"), std::string::npos);
  // A norm other than 2 or infinity is an invalid option, named before any work.
  options.flatten.p = 0.5;
  EXPECT_NE(message(b, b, options).find("map: p must be 2 or infinity, not 0.5"), std::string::npos)
      << message(b, b, options);
}

}  // namespace
}  // namespace liftmap
