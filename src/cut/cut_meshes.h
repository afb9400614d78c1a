#pragma once
/// Step 1 of the pipeline (paper §3.4): cut both meshes to disks along a common tree of paths through the
/// landmarks, with a vertex-to-vertex correspondence nu of the two boundaries.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "core/mesh.h"
#include "core/surface_point.h"

namespace liftmap {

/// Options of `cut_meshes`.
struct CutOptions {
  enum class Tree {
    kMinimumSpanning,  ///< minimum spanning tree on dist_M + dist_N (the paper's choice)
    kPath,             ///< a path through all landmarks (maximum degree 2)
  };
  Tree tree = Tree::kMinimumSpanning;
  bool geodesic_paths = true;  ///< search paths across faces and straighten them toward geodesics; if false,
                               ///< paths are shortest edge paths (cheaper, about 5-15% longer)
  double snap = 0.1;           ///< boundary vertices closer than this fraction of an edge are paired, not inserted
  /// Re-triangulate every input face that the paths cross as a constrained Delaunay triangulation of its corners,
  /// path vertices and path segments (remesh_along_paths), dropping the vertices of intermediate paths. If false,
  /// the refined mesh keeps the ear-clipped triangulation of the repeated insertions (caps and slivers along the
  /// paths, and different connectivity on a mesh and its moved copy).
  bool remesh = true;
};

/// One mesh after cutting.
struct CutSide {
  Eigen::MatrixXd V;                    ///< #Vr by 3 positions of the refined mesh (paths run along its edges)
  Eigen::MatrixXi F;                    ///< #F by 3 faces of the refined mesh (closed)
  std::vector<SurfacePoint> on_input;   ///< #Vr: each refined vertex as a face point of the input mesh
  Eigen::VectorXi face_to_input;        ///< #F: the input face containing each refined face
  Eigen::MatrixXi F_cut;                ///< #F by 3 faces of the cut mesh (a disk); face i is refined face i
  Eigen::VectorXi cut_to_refined;       ///< #Vc: each cut vertex's refined vertex
  std::vector<int> landmarks;           ///< k: refined vertex of each landmark
  std::vector<std::vector<int>> paths;  ///< per tree edge, refined vertices from child to parent landmark
  std::vector<double> path_lengths;     ///< per tree edge, length of its path
};

/// The two cut disks and their boundary correspondence.
struct CutResult {
  CutSide a, b;
  std::vector<std::array<int, 2>> tree;  ///< k - 1 tree edges {parent, child} (landmark indices)
  std::vector<std::array<int, 2>> nu;    ///< boundary pairs {cut vertex of A, cut vertex of B}, counter-clockwise
};

/// Cuts two closed genus-0 meshes to disks along a common tree through corresponding landmarks.
/// \param VA, VB #V by 3 positions; FA, FB #F by 3 faces (counter-clockwise)
/// \param landmarks_a, landmarks_b k >= 2 points each (vertex, edge or face points of the input connectivity, a
///        face point's barycentric coordinates in the order of its row of F); landmark i of A corresponds to
///        landmark i of B. A point that is not a vertex becomes a vertex of the refined mesh (insert_landmarks)
///        before the tree is traced; input vertex i is refined vertex i.
/// \return refined and cut meshes with provenance; every cut mesh is a disk (one boundary loop, Euler
///         characteristic 1) and nu is a bijection of the boundary vertices preserving their cyclic order and
///         taking landmark copies to copies of the same landmark.
/// \throw InvalidInputError if a mesh is not closed genus 0 and connected, the landmark counts differ, k < 2, a
///        landmark's vertex, edge or face is out of range or has no face, a face point's coordinates are not
///        finite, non-negative and summing to 1, or two landmarks of one side are at one point.
/// \throw PipelineError if an internal invariant fails (a bug).
/// The two meshes' steps run on two of the calling thread's OpenMP threads where it has two (omp_set_num_threads,
/// MapOptions::threads); the result is bitwise the same on one thread.
CutResult cut_meshes(const Eigen::MatrixXd& VA, const Eigen::MatrixXi& FA, const Eigen::MatrixXd& VB,
                     const Eigen::MatrixXi& FB, const std::vector<SurfacePoint>& landmarks_a,
                     const std::vector<SurfacePoint>& landmarks_b, const CutOptions& options = {});

/// cut_meshes with landmarks on vertices.
CutResult cut_meshes(const Eigen::MatrixXd& VA, const Eigen::MatrixXi& FA, const Eigen::MatrixXd& VB,
                     const Eigen::MatrixXi& FB, const std::vector<VertexId>& landmarks_a,
                     const std::vector<VertexId>& landmarks_b, const CutOptions& options = {});

/// Vertex landmarks as surface points.
std::vector<SurfacePoint> vertex_points(const std::vector<VertexId>& vertices);

}  // namespace liftmap
