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

TEST(CheckMesh, InsideOutMeshIsReported) {
  // Consistently oriented, closed, genus 0, but every normal points inward: it used to map "successfully", with
  // a 21.7% error against the true map.
  for (const char* name : {"camel.off", "larger_sphere.off"}) {
    SCOPED_TRACE(name);
    TriangleMesh m = testing::read_demo_mesh(name);
    m.F.col(1).swap(m.F.col(2));
    const MeshReport r = check_mesh(m.V, m.F);
    EXPECT_FALSE(r.mappable());
    EXPECT_TRUE(has_problem(r, "inside-out mesh", "the faces are oriented inward (signed volume -")) << r.summary();
    EXPECT_EQ(r.genus, 0) << "an inside-out mesh is still a genus-0 surface";
    EXPECT_THROW(require_mappable(r, name), InvalidInputError);
  }
}

TEST(CheckMesh, CoordinatesThePipelineCannotHandleAreReported) {
  const TriangleMesh camel = testing::read_demo_mesh("camel.off");
  struct Case {
    double scale, offset;
    const char* kind;
    const char* example;
  };
  // Each of these was "mappable" while `map` failed on it ("cut: mesh A is not connected", "jacobian_operator:
  // face 161 is degenerate").
  const Case cases[] = {
      {1e307, 0, "coordinate out of range", "beyond +-1e+30: scale the mesh down"},
      {1e31, 0, "coordinate out of range", "beyond +-1e+30"},
      {1e-31, 0, "coordinate out of range", "is below 1e-30: scale the mesh up"},
      {1, 1e12, "mesh far from the origin", "times the bounding box diagonal"},
      {1, 1e5, "mesh far from the origin", "(at most 1e+04)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::to_string(c.scale) + " " + std::to_string(c.offset));
    const Eigen::MatrixXd V = (camel.V * c.scale).array() + c.offset;
    const MeshReport r = check_mesh(V, camel.F);
    EXPECT_FALSE(r.mappable());
    EXPECT_TRUE(has_problem(r, c.kind, c.example)) << r.summary();
  }
  // Inside the limits the mesh stays mappable (tests/cli/input_validation.sh maps such copies).
  for (const auto& [scale, offset] : {std::pair{1e29, 0.0}, std::pair{1e-29, 0.0}, std::pair{1.0, 1e3}}) {
    const Eigen::MatrixXd V = (camel.V * scale).array() + offset;
    EXPECT_TRUE(check_mesh(V, camel.F).mappable())
        << scale << " " << offset << ": " << check_mesh(V, camel.F).summary();
  }
}

TEST(CheckMesh, EdgeFarShorterThanTheMeshIsReported) {
  // A tetrahedron with one vertex 1e-9 of the size away from another: no face is a sliver by its own shape
  // test's standard, but the mesh spans 1e9 of its shortest edge.
  Eigen::MatrixXd V(5, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1e-9, 1e-9, 1e-9;
  Eigen::MatrixXi F(6, 3);
  F << 0, 2, 1, 1, 2, 3, 0, 1, 4, 1, 3, 4, 3, 2, 4, 2, 0, 4;
  const MeshReport r = check_mesh(V, F);
  EXPECT_TRUE(has_problem(r, "edge too short for the mesh's extent", "of the bounding box diagonal (at least 1e-08)"))
      << r.summary();
}

TEST(CheckMesh, BoundaryLoopsAreUndefinedWhereTheBoundaryEdgesAreNot) {
  // check printed "boundary loops: 0" beside "boundary edge (12)" for a non-manifold mesh.
  const TriangleMesh m = read_mesh(testing::test_data("bad/nonmanifold_edge.off"));
  const MeshReport r = check_mesh(m.V, m.F);
  EXPECT_FALSE(r.n_boundary_loops.has_value());
  const TriangleMesh open = read_mesh(testing::test_data("bad/single_triangle.off"));
  const MeshReport o = check_mesh(open.V, open.F);
  EXPECT_EQ(o.n_boundary_edges, 3);
  EXPECT_EQ(o.n_boundary_loops, 1);
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
