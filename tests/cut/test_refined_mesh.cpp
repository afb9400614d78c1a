#include "cut/refined_mesh.h"

#include <gtest/gtest.h>

#include <random>

#include "cut_test_util.h"

namespace liftmap {
namespace {

// Random edge splits and chords keep the surface: same area, closed genus 0, provenance on the input.
TEST(cut_refined_mesh, RandomSplitsKeepTheSurface) {
  const auto in = test::load("hand");
  const Mesh input(in.F, static_cast<int>(in.V.rows()));
  RefinedMesh r = make_refined_mesh(input, in.V);
  std::mt19937 rng(7);
  for (int round = 0; round < 5; ++round) {
    std::vector<EdgeSplit> splits;
    std::vector<std::array<int, 2>> chords;
    std::vector<char> face_used(static_cast<size_t>(r.mesh.n_faces()), 0);
    const int n_old = r.n_vertices();
    for (int i = 0; i < 200; ++i) {
      const FaceId f(static_cast<int>(rng() % static_cast<unsigned>(r.mesh.n_faces())));
      const auto fh = r.mesh.face_halfedges(f);
      // Skip faces whose neighbours were used this round, to keep at most one chord per face.
      bool busy = face_used[static_cast<size_t>(f.idx)] != 0;
      for (const HalfedgeId h : fh) busy = busy || face_used[static_cast<size_t>(r.mesh.face(Mesh::twin(h)).idx)];
      if (busy) continue;
      face_used[static_cast<size_t>(f.idx)] = 1;
      for (const HalfedgeId h : fh) face_used[static_cast<size_t>(r.mesh.face(Mesh::twin(h)).idx)] = 1;
      // Split two edges of f at random points and join them; three points on the third edge, no chord.
      const double t0 = std::uniform_real_distribution<double>(0.05, 0.95)(rng);
      const double t1 = std::uniform_real_distribution<double>(0.05, 0.95)(rng);
      const int id0 = n_old + static_cast<int>(splits.size());
      splits.push_back({r.mesh.tail(fh[0]).idx, r.mesh.head(fh[0]).idx, t0});
      splits.push_back({r.mesh.tail(fh[1]).idx, r.mesh.head(fh[1]).idx, t1});
      chords.push_back({id0, id0 + 1});
      for (const double t : {0.2, 0.5, 0.7}) splits.push_back({r.mesh.tail(fh[2]).idx, r.mesh.head(fh[2]).idx, t});
    }
    split_refined_mesh(r, input, splits, chords);
    for (const auto& c : chords) {
      EXPECT_TRUE(find_halfedge(r.mesh, VertexId(c[0]), VertexId(c[1])).valid());
    }
  }
  EXPECT_EQ(r.mesh.euler_characteristic(), 2);
  EXPECT_TRUE(r.mesh.boundary_loops().empty());
  EXPECT_NEAR(test::area(r.vertex_matrix(), r.face_matrix()), test::area(in.V, in.F), 1e-9 * test::area(in.V, in.F));
  const double scale = (in.V.colwise().maxCoeff() - in.V.colwise().minCoeff()).norm();
  for (int v = 0; v < r.n_vertices(); ++v) {
    EXPECT_LT(
        (interpolate(input, in.V, r.on_input[static_cast<size_t>(v)]) - r.positions[static_cast<size_t>(v)].transpose())
            .norm(),
        1e-12 * scale);
  }
  // No degenerate face.
  for (const auto& f : r.faces) {
    const Eigen::Vector3d a = r.positions[static_cast<size_t>(f[0])], b = r.positions[static_cast<size_t>(f[1])],
                          c = r.positions[static_cast<size_t>(f[2])];
    EXPECT_GT((b - a).cross(c - a).norm(), 0.0);
  }
}

}  // namespace
}  // namespace liftmap
