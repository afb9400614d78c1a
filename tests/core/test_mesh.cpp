#include "core/mesh.h"

#include <gtest/gtest.h>

#include <set>

#include "common/test_meshes.h"
#include "core/errors.h"

namespace liftmap {
namespace {

// Checks every connectivity invariant of the halfedge structure.
void expect_consistent(const Mesh& m, const Eigen::MatrixXi& F) {
  ASSERT_EQ(m.faces(), F) << "face_vertices must return the input order";
  for (int h = 0; h < m.n_halfedges(); ++h) {
    const HalfedgeId he(h);
    ASSERT_EQ(m.next(m.prev(he)), he);
    ASSERT_EQ(m.prev(m.next(he)), he);
    ASSERT_EQ(Mesh::twin(Mesh::twin(he)), he);
    ASSERT_EQ(m.head(he), m.tail(m.next(he)));
    ASSERT_EQ(m.tail(Mesh::twin(he)), m.head(he));
    ASSERT_FALSE(m.is_boundary(he) && m.is_boundary(Mesh::twin(he))) << "an edge needs a face";
    if (!m.is_boundary(he)) {
      ASSERT_EQ(m.next(m.next(m.next(he))), he) << "faces are triangles";
      ASSERT_EQ(m.face(m.next(he)), m.face(he));
    }
  }
  long degree_sum = 0;
  for (int v = 0; v < m.n_vertices(); ++v) {
    std::set<int> seen;
    m.for_each_outgoing(VertexId(v), [&](HalfedgeId h) {
      EXPECT_EQ(m.tail(h), VertexId(v));
      EXPECT_TRUE(seen.insert(h.idx).second) << "fan of vertex " << v << " revisits a halfedge";
    });
    degree_sum += m.degree(VertexId(v));
    if (m.is_boundary(VertexId(v))) {
      EXPECT_TRUE(m.is_boundary(Mesh::twin(m.halfedge(VertexId(v)))));
    }
  }
  EXPECT_EQ(degree_sum, 2L * m.n_edges());
}

TEST(Mesh, RealGenusZeroMeshesAreConsistentSpheres) {
  for (const char* name : testing::kGenusZeroMeshes) {
    SCOPED_TRACE(name);
    const TriangleMesh tm = testing::read_demo_mesh(name);
    const Mesh m(tm.F, static_cast<int>(tm.V.rows()));
    expect_consistent(m, tm.F);
    EXPECT_EQ(m.euler_characteristic(), 2);
    EXPECT_TRUE(m.boundary_loops().empty());
    EXPECT_EQ(2 * m.n_edges(), 3 * m.n_faces());
  }
}

TEST(Mesh, BoundaryLoopsOfAnOpenMesh) {
  const TriangleMesh tm = testing::read_demo_mesh("camel.off");
  // Remove the star of vertex 0 and the star of a far vertex: a sphere with two holes.
  const int far = static_cast<int>(tm.V.rows()) - 1;
  std::vector<int> keep;
  for (int f = 0; f < tm.F.rows(); ++f) {
    if ((tm.F.row(f).array() != 0).all() && (tm.F.row(f).array() != far).all()) keep.push_back(f);
  }
  Eigen::MatrixXi F(static_cast<Eigen::Index>(keep.size()), 3);
  for (size_t i = 0; i < keep.size(); ++i) F.row(static_cast<Eigen::Index>(i)) = tm.F.row(keep[i]);
  const Mesh m(F, static_cast<int>(tm.V.rows()));
  expect_consistent(m, F);
  const auto loops = m.boundary_loops();
  ASSERT_EQ(loops.size(), 2U);
  for (const auto& loop : loops) {
    for (size_t i = 0; i < loop.size(); ++i) {
      EXPECT_TRUE(m.is_boundary(loop[i]));
      EXPECT_EQ(m.next(loop[i]), loop[(i + 1) % loop.size()]);
      EXPECT_TRUE(m.is_boundary(m.tail(loop[i])));
    }
  }
  EXPECT_TRUE(m.is_isolated(VertexId(0)));
  EXPECT_EQ(m.euler_characteristic(), 0);  // annulus
}

TEST(Mesh, RejectsNonManifoldInputNamingTheElement) {
  Eigen::MatrixXi three_faces_on_edge(3, 3);
  three_faces_on_edge << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  try {
    const Mesh m(three_faces_on_edge, 5);
    FAIL() << "expected InvalidInputError";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("edge (0, 1) is shared by 3 faces"), std::string::npos) << e.what();
  }
  Eigen::MatrixXi flipped(2, 3);
  flipped << 0, 1, 2, 0, 1, 3;
  EXPECT_THROW(Mesh(flipped, 4), InvalidInputError);
  Eigen::MatrixXi out_of_range(1, 3);
  out_of_range << 0, 1, 7;
  EXPECT_THROW(Mesh(out_of_range, 3), InvalidInputError);
  Eigen::MatrixXi bowtie(2, 3);  // two triangles touching at vertex 0
  bowtie << 0, 1, 2, 0, 3, 4;
  EXPECT_THROW(Mesh(bowtie, 5), InvalidInputError);
}

}  // namespace
}  // namespace liftmap
