#pragma once
// Liftable (and non-liftable) pairs of flattened disks for the lifting tests and benchmark.

#include <Eigen/Core>
#include <vector>

#include "core/mesh.h"
#include "core/surface_point.h"
#include "io/read_mesh.h"

namespace liftmap::testing {

/// A disk with a flattening.
struct FlatDisk {
  Eigen::MatrixXd V;  ///< #V by 3 positions (hand-built disks: the flattening lifted to a surface in R^3)
  Eigen::MatrixXi F;  ///< #F by 3
  Eigen::MatrixXd X;  ///< #V by 2 flattening
  Eigen::MatrixXd P;  ///< #V by 2 parameter-domain coordinates of hand-built disks (ground truth), else empty
};

/// Two flattened disks with a common boundary and the boundary correspondence nu (#B by 2).
struct FlatPair {
  FlatDisk m;
  FlatDisk n;
  Eigen::MatrixXi nu;
};

/// Grid disk on [0, nx] x [0, ny] with integer vertex coordinates (vertex (i, j) has index j * (nx + 1) + i),
/// every cell split along its "/" diagonal if `slash`, else along its "\" diagonal.
FlatDisk grid_disk(int nx, int ny, bool slash);

/// The boundary of `a` and `b` matched by identical coordinates (both must have the same boundary points).
Eigen::MatrixXi match_boundaries(const FlatDisk& a, const FlatDisk& b);

/// A strip [1, 2] x [0, turns * 2 * pi] in polar parameters (r, theta), flattened by
/// (r, theta) -> (r cos theta, r sin theta): for turns > 1 the flattening overlaps itself, winding several times
/// around the points of the annulus (paper Figure 3). `nr` by `nt` samples. With `jitter`, interior vertices are
/// moved pseudo-randomly by up to `jitter` of a cell in parameter space and the diagonals alternate. The
/// boundary depends only on (nr, nt, turns), so two strips with the same ones share it exactly.
FlatDisk spiral_strip(int nr, int nt, double turns, double jitter);

/// Midpoint subdivision: every face split into four.
TriangleMesh subdivide(const TriangleMesh& mesh);

/// The Tutte pair of two disks with equally many boundary vertices: boundary vertex k of each (counter-clockwise
/// from the first of `ccw_boundary_loop`) at angle 2 pi k / n on the ellipse with semi-axes `radii` (the unit
/// circle by default), interior by mean-value Tutte.
FlatPair tutte_pair(const TriangleMesh& a, const TriangleMesh& b, const Eigen::Vector2d& radii = {1, 1});

/// Two disk patches of about `n_faces` faces of two closed meshes, grown in order of geodesic distance from the
/// best of four seeds, without notches or ears (slivers in a Tutte embedding), the one with fewer boundary
/// vertices trimmed along its boundary until both have equally many, as a Tutte pair.
FlatPair tutte_pair_of_patches(const TriangleMesh& a, const TriangleMesh& b, int n_faces,
                               const Eigen::Vector2d& radii = {1, 1});

/// Maps both flattenings by z -> exp(lambda z) (complex): locally injective, the boundary stays common, and for
/// lambda > pi the disk winds more than once around the origin.
void exp_warp(FlatPair& pair, double lambda);

/// All minimal elements (vertex, edge or face) of the flattening X of `mesh` that contain z, by exact
/// predicates over every face (brute-force point location, for ground truth).
class PointLocator {
 public:
  PointLocator(const Mesh& mesh, const Eigen::MatrixXd& X);
  [[nodiscard]] std::vector<SurfacePoint> locate(const Eigen::Vector2d& z) const;

 private:
  const Mesh& mesh_;
  const Eigen::MatrixXd& X_;
  Eigen::Vector2d lo_, cell_;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<int>> buckets_;
};

/// True if p and q are the same vertex, the same edge or the same face.
bool same_element(const SurfacePoint& p, const SurfacePoint& q);

}  // namespace liftmap::testing
