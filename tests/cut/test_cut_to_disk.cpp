#include "cut/cut_to_disk.h"

#include <gtest/gtest.h>

#include "cut/refined_mesh.h"

namespace liftmap {
namespace {

// Octahedron: vertices +x, -x, +y, -y, +z, -z.
Mesh octahedron() {
  Eigen::MatrixXi F(8, 3);
  F << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  return Mesh(F, 6);
}

CutDisk cut_along(const Mesh& mesh, const std::vector<std::array<int, 2>>& edges) {
  std::vector<char> is_cut(static_cast<size_t>(mesh.n_edges()), 0);
  for (const auto& e : edges) {
    const HalfedgeId h = find_halfedge(mesh, VertexId(e[0]), VertexId(e[1]));
    EXPECT_TRUE(h.valid());
    is_cut[static_cast<size_t>(Mesh::edge(h).idx)] = 1;
  }
  return cut_to_disk(mesh, is_cut);
}

TEST(cut_to_disk, TwoEdgeSlit) {
  const Mesh mesh = octahedron();
  const CutDisk d = cut_along(mesh, {{4, 0}, {0, 5}});
  EXPECT_EQ(d.to_refined.size(), 7);  // a slit's two ends are not duplicated, its middle vertex is
  const Mesh cut(d.F, static_cast<int>(d.to_refined.size()));
  ASSERT_EQ(cut.boundary_loops().size(), 1u);
  EXPECT_EQ(cut.boundary_loops()[0].size(), 4u);
  EXPECT_EQ(cut.euler_characteristic(), 1);
}

TEST(cut_to_disk, TreeWithABranchVertex) {
  const Mesh mesh = octahedron();
  // Star at vertex 4 with three branches: 4 gets three copies, the leaves one each.
  const CutDisk d = cut_along(mesh, {{4, 0}, {4, 1}, {4, 2}});
  EXPECT_EQ(d.to_refined.size(), 8);
  const Mesh cut(d.F, static_cast<int>(d.to_refined.size()));
  ASSERT_EQ(cut.boundary_loops().size(), 1u);
  EXPECT_EQ(cut.boundary_loops()[0].size(), 6u);
  EXPECT_EQ(cut.euler_characteristic(), 1);
  // Faces keep their vertices up to duplication.
  const Eigen::MatrixXi F = mesh.faces();
  for (int f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) EXPECT_EQ(d.to_refined(d.F(f, k)), F(f, k));
  }
}

TEST(cut_to_disk, NoCutKeepsTheMesh) {
  const Mesh mesh = octahedron();
  const CutDisk d = cut_along(mesh, {});
  EXPECT_EQ(d.to_refined.size(), 6);
  EXPECT_EQ(Mesh(d.F, 6).euler_characteristic(), 2);
}

}  // namespace
}  // namespace liftmap
