#include "check/check_mesh.h"

#include <gtest/gtest.h>

#include "common/test_meshes.h"
#include "core/errors.h"

namespace liftmap {
namespace {

bool has_problem(const MeshReport& r, const std::string& kind, const std::string& example) {
  for (const auto& p : r.problems) {
    if (p.kind != kind) continue;
    for (const auto& e : p.examples) {
      if (e.find(example) != std::string::npos) return true;
    }
  }
  return false;
}

TEST(CheckMesh, GenusZeroDemoMeshesAreMappable) {
  for (const char* name : testing::kGenusZeroMeshes) {
    SCOPED_TRACE(name);
    const TriangleMesh m = testing::read_demo_mesh(name);
    const MeshReport r = check_mesh(m.V, m.F);
    EXPECT_TRUE(r.mappable()) << r.summary();
    EXPECT_EQ(r.genus, 0);
    EXPECT_EQ(r.euler_characteristic, 2);
    EXPECT_EQ(r.n_components, 1);
    EXPECT_EQ(r.n_edges, 3 * r.n_faces / 2);
  }
}

TEST(CheckMesh, ExplainsWhyOtherDemoMeshesCannotBeMapped) {
  const TriangleMesh elephant = testing::read_demo_mesh("elephant.off");
  const MeshReport e = check_mesh(elephant.V, elephant.F);
  EXPECT_EQ(e.genus, 3);
  EXPECT_TRUE(has_problem(e, "wrong genus", "genus 3: only genus 0 is supported"));

  const TriangleMesh head = testing::read_demo_mesh("head.off");
  const MeshReport h = check_mesh(head.V, head.F);
  EXPECT_EQ(h.n_boundary_loops, 3);
  EXPECT_TRUE(has_problem(h, "open mesh", "3 boundary loop(s)"));

  const TriangleMesh bones = testing::read_demo_mesh("bones.off");
  const MeshReport b = check_mesh(bones.V, bones.F);
  EXPECT_EQ(b.n_components, 26);
  EXPECT_FALSE(b.mappable());
  EXPECT_THROW(require_mappable(b, "bones.off"), InvalidInputError);
}

TEST(CheckMesh, NamesTheOffendingElements) {
  struct Case {
    const char* file;
    const char* kind;
    const char* example;
  };
  const Case cases[] = {
      {"bad/nonmanifold_edge.off", "non-manifold edge", "edge (0, 1) is shared by 3 faces"},
      {"bad/nonmanifold_vertex.off", "non-manifold vertex", "vertex 0 joins separate fans"},
      {"bad/flipped_face.off", "inconsistent orientation", "faces 0 and 4 disagree"},
      {"bad/degenerate_face.off", "degenerate face", "face 8 (0, 1, 6)"},
      {"bad/duplicate_face.off", "duplicate face", "faces 0 and 1 have the same vertices"},
      {"bad/unreferenced_vertex.off", "unreferenced vertex", "vertex 6 is used by no face"},
      {"bad/nan_coordinate.off", "non-finite coordinate", "vertex 4"},
      {"bad/torus.off", "wrong genus", "genus 1"},
      {"bad/two_components.off", "disconnected mesh", "2 connected components"},
      {"bad/single_triangle.off", "boundary edge", "edge (0, 1) has only one face"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    const TriangleMesh m = read_mesh(testing::test_data(c.file));
    const MeshReport r = check_mesh(m.V, m.F);
    EXPECT_FALSE(r.mappable());
    EXPECT_TRUE(has_problem(r, c.kind, c.example)) << r.summary();
  }
}

TEST(CheckMesh, SliverThatIsNotDegenerateIsAccepted) {
  // A thin but valid tetrahedron: heights of 1e-6 relative to the edges are fine.
  Eigen::MatrixXd V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0.5, 1e-6, 0, 0.5, 0.3, 1;
  Eigen::MatrixXi F(4, 3);
  F << 0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3;
  const MeshReport r = check_mesh(V, F);
  EXPECT_TRUE(r.mappable()) << r.summary();
}

}  // namespace
}  // namespace liftmap
