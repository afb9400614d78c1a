// A mesh mapped onto a scaled copy of itself must give the identity: the cut, the flattenings and the lift are all
// invariant under scaling (both meshes are normalised to the same area), so any deviation is a symmetry the
// pipeline breaks. Before the cut compared arc lengths in units of sqrt(area), a copy scaled by 2 gave f a max
// distortion of 25 to 45.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <numeric>
#include <random>
#include <set>
#include <string>

#include "common/test_meshes.h"
#include "map/map_meshes.h"

namespace liftmap {
namespace {

/// A copy of a mesh: positions x -> scale * R x + t, vertex i of the original is vertex perm[i] of the copy.
struct MovedCopy {
  TriangleMesh mesh;
  std::vector<int> perm;  ///< original vertex -> copy vertex
  double scale = 1;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
};

struct Motion {
  std::string name;
  double scale = 1;
  double angle = 0;  ///< about the axis (1, 2, 3)
  double shift = 0;  ///< translation (shift, -shift / 3, shift / 5)
  bool reorder = false;
};

MovedCopy move(const TriangleMesh& m, const Motion& motion, unsigned seed) {
  MovedCopy c;
  c.scale = motion.scale;
  c.R = Eigen::AngleAxisd(motion.angle, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  c.t = motion.shift * Eigen::Vector3d(1, -1.0 / 3, 1.0 / 5);
  const auto nv = static_cast<int>(m.V.rows());
  const auto nf = static_cast<int>(m.F.rows());
  c.perm.resize(static_cast<size_t>(nv));
  std::iota(c.perm.begin(), c.perm.end(), 0);
  std::vector<int> face_order(static_cast<size_t>(nf));
  std::iota(face_order.begin(), face_order.end(), 0);
  std::mt19937 rng(seed);
  if (motion.reorder) {
    std::shuffle(c.perm.begin(), c.perm.end(), rng);
    std::shuffle(face_order.begin(), face_order.end(), rng);
  }
  c.mesh.V.resize(nv, 3);
  for (int v = 0; v < nv; ++v) {
    const Eigen::Vector3d x = m.V.row(v).transpose();
    c.mesh.V.row(c.perm[static_cast<size_t>(v)]) = (c.scale * (c.R * x) + c.t).transpose();
  }
  c.mesh.F.resize(nf, 3);
  for (int f = 0; f < nf; ++f) {
    const int src = face_order[static_cast<size_t>(f)];
    const int shift = motion.reorder ? static_cast<int>(rng() % 3) : 0;  // rotate the corners, keep orientation
    for (int k = 0; k < 3; ++k) c.mesh.F(f, k) = c.perm[static_cast<size_t>(m.F(src, (k + shift) % 3))];
  }
  return c;
}

using testing::position;
using testing::sqrt_area;

std::vector<VertexId> random_landmarks(int n_vertices, int k, unsigned seed) {
  std::mt19937 rng(seed);
  std::set<int> chosen;
  std::vector<VertexId> out;
  while (static_cast<int>(out.size()) < k) {
    const int v = static_cast<int>(rng() % static_cast<unsigned>(n_vertices));
    if (chosen.insert(v).second) out.emplace_back(v);
  }
  return out;
}

struct IdentityError {
  double mean = 0, max = 0;  ///< |f(v) - moved(v)| / sqrt(area of the copy), over A's vertices
};

IdentityError identity_error(const std::vector<SurfacePoint>& a_to_b, const TriangleMesh& a, const MovedCopy& b) {
  IdentityError e;
  const double unit = sqrt_area(b.mesh);
  for (Eigen::Index v = 0; v < a.V.rows(); ++v) {
    const Eigen::Vector3d truth = b.scale * (b.R * a.V.row(v).transpose()) + b.t;
    const double d = (position(b.mesh, a_to_b[static_cast<size_t>(v)]) - truth).norm() / unit;
    e.mean += d / static_cast<double>(a.V.rows());
    e.max = std::max(e.max, d);
  }
  return e;
}

struct Case {
  const char* mesh;
  int k;
  Motion motion;
  int max_iterations;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.mesh << " k=" << c.k << " " << c.motion.name; }

class MovedCopyIsIdentity : public ::testing::TestWithParam<Case> {};

TEST_P(MovedCopyIsIdentity, ErrorAndDistortion) {
  const Case& c = GetParam();
  const TriangleMesh a = testing::read_demo_mesh(c.mesh);
  ASSERT_GT(a.V.rows(), 0);
  const MovedCopy b = move(a, c.motion, 7);
  const auto la = random_landmarks(static_cast<int>(a.V.rows()), c.k, 11);
  std::vector<VertexId> lb;
  for (const VertexId v : la) lb.emplace_back(b.perm[static_cast<size_t>(v.idx)]);
  MapOptions options;
  options.flatten.max_iterations = c.max_iterations;  // the identity holds after any number of outer iterations
  const MapResult map = map_meshes(a.V, a.F, b.mesh.V, b.mesh.F, la, lb, options);
  EXPECT_TRUE(map.verification.passed) << (map.verification.failures.empty() ? "" : map.verification.failures.front());
  EXPECT_EQ(map.cut.a.F_cut.rows(), map.cut.b.F_cut.rows()) << "the two cut disks differ";
  const IdentityError e = identity_error(map.a_to_b, a, b);
  EXPECT_LT(e.max, 1e-8) << "mean " << e.mean;
  EXPECT_LT(map.distortion_f.max, 1 + 1e-6);
  EXPECT_LT(map.distortion_g.max, 1 + 1e-6);
}

// Scalings by powers of two are exact in floating point, so every comparison the pipeline makes comes out the same on
// the copy: the map must be the identity to rounding. (Rotations, translations and re-orderings round differently;
// the cut's path search then breaks exact ties between equally long paths differently on the two meshes, and the
// identity does not hold yet: issue 25.)
const Motion kScale2{"scaled by 2", 2};
const Motion kScaleSmall{"scaled by 2^-10", 1.0 / 1024};

std::vector<Case> cases() {
  std::vector<Case> out;
  for (const char* mesh : {"larger_sphere.off", "ellipsoid.off"}) {
    for (const int k : {2, 6, 15}) {
      for (const Motion& m : {kScale2, kScaleSmall}) out.push_back({mesh, k, m, 100});
    }
  }
  // The examples' other meshes and three more, on the start flattening (the identity holds after any number of
  // outer iterations; the full runs would take minutes).
  for (const char* mesh :
       {"camel.off", "cow.off", "homer.off", "fandisk.off", "bull.off", "dino.off", "triceratops.off"}) {
    out.push_back({mesh, 2, kScaleSmall, 0});
    out.push_back({mesh, 6, kScale2, 0});
    out.push_back({mesh, 15, kScaleSmall, 0});
  }
  return out;
}

INSTANTIATE_TEST_SUITE_P(Meshes, MovedCopyIsIdentity, ::testing::ValuesIn(cases()));

}  // namespace
}  // namespace liftmap
