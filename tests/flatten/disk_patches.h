#pragma once
/// Disk-shaped test inputs for the flattening stage, cut from the real meshes without the cut stage.

#include <Eigen/Core>
#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/mesh.h"
#include "flatten/joint_flatten.h"

namespace liftmap::testing {

/// A disk with its connectivity and counter-clockwise boundary loop.
struct TestDisk {
  Eigen::MatrixXd V;  ///< #V by 3
  Eigen::MatrixXi F;  ///< #F by 3
  std::unique_ptr<Mesh> mesh;
  std::vector<VertexId> boundary;

  [[nodiscard]] FlatteningDisk flattening_disk() const { return {mesh.get(), V, boundary}; }
};

/// Reads a mesh of LIFTMAP_DATA_DIR, e.g. "camel.off".
void read_test_mesh(const std::string& name, Eigen::MatrixXd& V, Eigen::MatrixXi& F);

/// Grows a disk of faces around `seed_face` in breadth-first order, adding only faces that keep it a disk,
/// until it has `n_faces` faces and, if `n_boundary` > 0, exactly that many boundary vertices.
std::vector<int> grow_disk(const Eigen::MatrixXi& F, int n_vertices, int seed_face, int n_faces, int n_boundary = 0);

/// The sub-mesh of the listed faces (or of all other faces if `complement`), vertices re-indexed.
TestDisk make_disk(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<int>& faces,
                   bool complement = false);

/// A patch of about `n_faces` faces of the named mesh.
TestDisk mesh_patch(const std::string& name, int seed_face, int n_faces, int n_boundary = 0);

/// The same disk with a smooth non-isometric deformation applied to its vertices (same connectivity).
TestDisk deformed_copy(const TestDisk& d);

/// A patch of about `n_faces` faces of mesh a, and a patch of mesh b of at least n_faces/2 faces grown until its
/// boundary vertex count equals that of the first.
std::pair<TestDisk, TestDisk> patch_pair(const std::string& a, const std::string& b, int n_faces, int seed_a = 0,
                                         int seed_b = 0);

/// Two closed meshes each minus a small disk of faces (`hole_faces` on a; on b, grown until the boundary vertex
/// counts agree).
std::pair<TestDisk, TestDisk> punctured_pair(const std::string& a, const std::string& b, int hole_faces);

/// A capped tube of girth 2 pi and length `length_over_girth` times that, open at z = 0 (the disk's boundary) and
/// closed by a hemisphere: the shape of a part no cut enters. `around` vertices per ring, near-equilateral faces.
TestDisk capped_tube(double length_over_girth, int around = 16);

/// A planar disk: the grid of nx by ny squares (two triangles each) of [0, nx / ny] x [0, 1], its interior vertices
/// moved by up to `jitter` grid spacings in each coordinate (uniform, from std::mt19937(seed)).
TestDisk jittered_planar_grid(int nx, int ny, double jitter, unsigned seed);

/// One of the four (p, h) settings of problem (10), with a name for parametrised tests.
struct Combo {
  double p;
  DistortionCombiner h;
  const char* name;
};

inline constexpr std::array<Combo, 4> kAllCombos{
    Combo{2, DistortionCombiner::kNorm, "p2_norm"}, Combo{2, DistortionCombiner::kMax, "p2_max"},
    Combo{std::numeric_limits<double>::infinity(), DistortionCombiner::kNorm, "pinf_norm"},
    Combo{std::numeric_limits<double>::infinity(), DistortionCombiner::kMax, "pinf_max"}};

/// The first subproblem (10) of a camel-cow patch pair (300 faces each) with the setting's p and h: the instance of the
/// solver tests.
JointFlattenProblem camel_cow_patch_problem(const Combo& combo);

}  // namespace liftmap::testing
