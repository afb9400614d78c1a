#pragma once
/// Landmark files: corresponding points of mesh A and mesh B.
///
/// Format (text): one pair per line, `tokenA tokenB`. `#` starts a comment (whole line or trailing); blank lines
/// are ignored. A token is one of
/// - `123`: a vertex, by its 0-based index;
/// - `f812:0.2,0.3,0.5`: a point of face 812 (0-based row of F) with barycentric coordinates of its three corners
///   in the file's order, each in [0, 1] and summing to 1 (both within 1e-9; they are clamped and normalised; a
///   coordinate below 1e-3 is set to 0, which moves a point that near a side of its face onto it, with a warning);
/// - `0.1,-2.5,3`: a point of R^3, located at the nearest point of the surface (a warning says so if that is
///   farther than 1% of the bounding box diagonal).
/// No spaces inside a token.

#include <Eigen/Core>
#include <array>
#include <iosfwd>
#include <string>
#include <vector>

#include "core/mesh.h"
#include "core/surface_point.h"

namespace liftmap {

/// Corresponding landmarks: `a[i]` on mesh A corresponds to `b[i]` on mesh B. Each is a vertex point, or a face
/// point with barycentric coordinates in the order of the face's row of F (a point on an edge has one exact zero,
/// a face point never has two); no edge points, so the landmarks need no connectivity (the cut locates them).
struct Landmarks {
  std::vector<SurfacePoint> a;
  std::vector<SurfacePoint> b;
  std::vector<int> line;              ///< line of the file each pair came from (for messages)
  std::vector<std::string> warnings;  ///< for the user, naming file and line: 3D points far from the surface, points
                                      ///< moved onto a side of their face
};

/// Reads and validates a landmark file of vertex indices only against meshes with `n_vertices_a` and
/// `n_vertices_b` vertices (surface-point tokens need the meshes: the overload below).
/// \throw IoError if the file cannot be read; InvalidInputError naming the file and line for a malformed line,
///        an index out of range, a vertex used twice on one side, a surface-point token, or fewer than 2 pairs.
/// A UTF-8 byte-order mark before the first line is skipped.
Landmarks read_landmarks(const std::string& path, int n_vertices_a, int n_vertices_b);

/// read_landmarks (vertex indices only) from a stream; `name` stands for the file in messages.
Landmarks read_landmarks(std::istream& in, const std::string& name, int n_vertices_a, int n_vertices_b);

/// Reads and validates a landmark file with every token form against the two meshes.
/// \param VA, VB #V by 3 positions; FA, FB #F by 3 faces
/// \throw IoError if the file cannot be read; InvalidInputError naming the file and line for a malformed token,
///        a vertex or face out of range, barycentric coordinates that are not finite, outside [0, 1] or do not sum
///        to 1, two landmarks at one point of one side (naming both lines), two landmarks of one side, one of them in
///        a face, closer than 1e-6 of that face's size sqrt(area) (too close to cut apart; naming both lines), or
///        fewer than 2 pairs.
Landmarks read_landmarks(const std::string& path, const Eigen::MatrixXd& VA, const Eigen::MatrixXi& FA,
                         const Eigen::MatrixXd& VB, const Eigen::MatrixXi& FB);

/// read_landmarks with the meshes, from a stream; `name` stands for the file in messages.
Landmarks read_landmarks(std::istream& in, const std::string& name, const Eigen::MatrixXd& VA,
                         const Eigen::MatrixXi& FA, const Eigen::MatrixXd& VB, const Eigen::MatrixXi& FB);

/// Landmarks given as index pairs (e.g. a k by 2 array from Python), with the checks of read_landmarks.
/// \param pairs k pairs {vertex of A, vertex of B}
/// \param name how messages name the pairs; each message names the offending row (0-based)
/// \throw InvalidInputError naming the row for a negative or out-of-range index or a vertex used twice on one
///        side, or if there are fewer than 2 pairs.
Landmarks make_landmarks(const std::vector<std::array<long long, 2>>& pairs, const std::string& name, int n_vertices_a,
                         int n_vertices_b);

/// Landmarks given as surface points (e.g. face indices and barycentric coordinates from Python arrays), checked
/// and snapped as read_landmarks (with the meshes) checks and snaps a file's face points: a face point's
/// barycentric coordinates are in the order of its face's row of F, each in [0, 1] and summing to 1 (within 1e-9);
/// a coordinate below 1e-3 is set to 0 (a warning names the row), and a point with a coordinate of 1 becomes a
/// vertex point.
/// \param a, b k points each, a[i] on mesh A corresponding to b[i] on mesh B: vertex or face points
/// \param name how messages name the landmarks; each message names the offending row (0-based)
/// \throw InvalidInputError naming the row for an edge point, a vertex or face out of range, coordinates that are
///        not barycentric, two landmarks at one point of one side or too close to cut apart (as read_landmarks); or
///        if a and b differ in length, or k < 2.
Landmarks make_landmarks(const std::vector<SurfacePoint>& a, const std::vector<SurfacePoint>& b,
                         const std::string& name, const Eigen::MatrixXd& VA, const Eigen::MatrixXi& FA,
                         const Eigen::MatrixXd& VB, const Eigen::MatrixXi& FB);

/// The size of face `face` of (V, F): the square root of its area.
double face_size(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int face);

/// Why two landmarks of one side `distance` apart are too close to cut apart, or "" if they are not: closer than
/// 1e-6 of the size of the face they lie in (the smaller one; face_size, infinite for a vertex landmark). The cut
/// between two such points holds triangles too thin to flatten.
std::string too_close_to_cut(double distance, double size_p, double size_q);

/// Checks that no two face points among `points` (the landmarks of one mesh, as map_meshes takes them) are too close
/// to cut apart (too_close_to_cut). Points that are not valid face points of (V, F) are skipped (the cut names them).
/// \throw InvalidInputError naming `name` and both landmarks' indices (0-based).
void require_landmarks_apart(const std::vector<SurfacePoint>& points, const Eigen::MatrixXd& V,
                             const Eigen::MatrixXi& F, const std::string& name);

/// The token of a landmark in the format above: `123` for a vertex point, `f<face>:<b0>,<b1>,<b2>` for a face point
/// (each coordinate the shortest text that reads back as the same double).
/// \pre p is a vertex or face point
std::string landmark_token(const SurfacePoint& p);

/// Writes landmarks in the format above.
/// \throw IoError if the file cannot be written.
void write_landmarks(const std::string& path, const Landmarks& landmarks);

}  // namespace liftmap
