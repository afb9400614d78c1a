#pragma once
/// numpy arrays in and out of the Python module: the checks every array argument passes, with messages that name
/// the argument, and the conversions to and from the library's Eigen types.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/surface_point.h"
#include "io/landmarks.h"

namespace liftmap::python {

/// #V by 3 positions from a float64 or float32 array (C or Fortran order, any strides).
/// \throw InvalidInputError naming `name` for another dtype, a shape other than (n, 3), or a non-array.
Eigen::MatrixXd vertices_from(const pybind11::handle& array, const std::string& name);

/// #F by 3 vertex indices from an int32 or int64 array (C or Fortran order, any strides). Indices out of the
/// vertex range are left to check_mesh, which names the face; only those beyond int32 are rejected here.
/// \throw InvalidInputError naming `name` for another dtype, a shape other than (n, 3), an index beyond int32.
Eigen::MatrixXi faces_from(const pybind11::handle& array, const std::string& name);

/// k landmark pairs from a k by 2 integer array, checked as read_landmarks checks a file (make_landmarks).
/// \throw InvalidInputError naming "landmarks" and the row.
Landmarks landmarks_from(const pybind11::handle& array, int n_vertices_a, int n_vertices_b);

/// How face_points_from checks barycentric coordinates.
enum class CoordinateCheck {
  kStrict,        ///< each coordinate finite and >= -1e-12, each row summing to 1 within 1e-9
  kLeaveToCaller  ///< none: the caller checks them (make_landmarks, with a landmark file's tolerance)
};

/// Face points from n face indices (int32 or int64) and an n by 3 array of barycentric coordinates: each face in
/// 0..n_faces-1, the coordinates checked as `check` says.
/// \throw InvalidInputError naming the array (faces_name, barycentric_name) and the row.
std::vector<SurfacePoint> face_points_from(const pybind11::handle& faces, const pybind11::handle& barycentric,
                                           int n_faces, const std::string& faces_name = "faces",
                                           const std::string& barycentric_name = "barycentric",
                                           CoordinateCheck check = CoordinateCheck::kStrict);

/// Checks that every vertex index of F is in 0..n_vertices-1 (check_mesh checks it too, but surface points are placed
/// on the faces before it runs).
/// \throw InvalidInputError naming `name`, the face and the index.
void require_face_corners(const Eigen::MatrixXi& F, Eigen::Index n_vertices, const std::string& name);

/// Landmarks of the meshes (VA, FA) and (VB, FB) from Python: a k by 2 integer array of vertex pairs
/// (landmarks_from above), or a dict of face points {"faces_A": (k,) int, "barycentric_A": (k, 3) float, "faces_B",
/// "barycentric_B"}, barycentric coordinates in the order of the face's row of F, checked and snapped as a landmark
/// file's face points are (make_landmarks with the meshes; its warnings are in the result).
/// \throw InvalidInputError naming the key or array and the row.
Landmarks landmarks_from(const pybind11::handle& landmarks, const Eigen::MatrixXd& VA, const Eigen::MatrixXi& FA,
                         const Eigen::MatrixXd& VB, const Eigen::MatrixXi& FB);

/// Landmarks as the dict landmarks_from takes, every landmark a face point (a vertex as a corner of its first face
/// in F, barycentric coordinate 1 there).
pybind11::dict landmarks_dict(const Landmarks& landmarks, const Eigen::MatrixXi& FA, const Eigen::MatrixXi& FB);

/// Each of the landmarks' warnings as a Python UserWarning.
/// \throw pybind11::error_already_set if the warnings filter turns a warning into an exception.
void warn_landmarks(const Landmarks& landmarks);

/// Any numeric array of 1 or 2 dimensions as an n by k matrix (a 1-D array is n by 1), converted to float64.
/// \throw InvalidInputError naming `name` otherwise.
Eigen::MatrixXd values_from(const pybind11::handle& array, const std::string& name);

/// The faces (n,) int32 and barycentric coordinates (n, 3) float64 of face points, as numpy arrays.
pybind11::array_t<int> faces_of(const std::vector<SurfacePoint>& points);
pybind11::array_t<double> barycentric_of(const std::vector<SurfacePoint>& points);

/// A copy of a matrix as a C-order numpy array of the same shape.
template <typename Derived>
pybind11::array_t<typename Derived::Scalar> to_numpy(const Eigen::MatrixBase<Derived>& M) {
  using Scalar = typename Derived::Scalar;
  pybind11::array_t<Scalar> out({static_cast<pybind11::ssize_t>(M.rows()), static_cast<pybind11::ssize_t>(M.cols())});
  auto o = out.template mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < M.rows(); ++i) {
    for (Eigen::Index j = 0; j < M.cols(); ++j) o(i, j) = M(i, j);
  }
  return out;
}

/// A copy of an index list as a 1-D numpy array.
pybind11::array_t<int> to_numpy(const std::vector<int>& v);

}  // namespace liftmap::python
