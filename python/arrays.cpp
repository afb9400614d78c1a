#include "arrays.h"

#include <cmath>
#include <cstdint>
#include <limits>

#include "core/errors.h"

namespace py = pybind11;

namespace liftmap::python {

namespace {

/// The argument as a numpy array (a list of lists becomes one).
py::array as_array(const py::handle& h, const std::string& name) {
  py::array a = py::array::ensure(h);
  if (!a) {
    PyErr_Clear();
    throw InvalidInputError(name + ": expected a numpy array, got " +
                            std::string(py::str(h.get_type().attr("__name__"))));
  }
  return a;
}

std::string shape_of(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

std::string dtype_of(const py::array& a) { return py::str(a.dtype()); }

void require_columns(const py::array& a, const std::string& name, const std::string& shape, py::ssize_t columns) {
  if (a.ndim() != 2 || a.shape(1) != columns) {
    throw InvalidInputError(name + ": expected an array of shape " + shape + ", got shape " + shape_of(a));
  }
}

bool is_float(const py::array& a) { return a.dtype().kind() == 'f' && (a.itemsize() == 8 || a.itemsize() == 4); }
bool is_int(const py::array& a) { return a.dtype().kind() == 'i' && (a.itemsize() == 8 || a.itemsize() == 4); }

/// The array's integers, which is_int has checked, as int: those beyond int32 are named.
Eigen::MatrixXi int_matrix(const py::array& a, const std::string& name, const std::string& element) {
  const auto typed = py::array_t<std::int64_t, py::array::forcecast>::ensure(a);
  const auto x = typed.unchecked<2>();
  Eigen::MatrixXi M(x.shape(0), x.shape(1));
  for (py::ssize_t i = 0; i < x.shape(0); ++i) {
    for (py::ssize_t j = 0; j < x.shape(1); ++j) {
      if (x(i, j) < std::numeric_limits<int>::min() || x(i, j) > std::numeric_limits<int>::max()) {
        throw InvalidInputError(name + ": " + element + " " + std::to_string(i) + " has index " +
                                std::to_string(x(i, j)) + ", beyond the int32 range");
      }
      M(i, j) = static_cast<int>(x(i, j));
    }
  }
  return M;
}

Eigen::MatrixXd double_matrix(const py::array& a) {
  const auto typed = py::array_t<double, py::array::forcecast>::ensure(a);
  const auto x = typed.unchecked<2>();
  Eigen::MatrixXd M(x.shape(0), x.shape(1));
  for (py::ssize_t i = 0; i < x.shape(0); ++i) {
    for (py::ssize_t j = 0; j < x.shape(1); ++j) M(i, j) = x(i, j);
  }
  return M;
}

}  // namespace

Eigen::MatrixXd vertices_from(const py::handle& array, const std::string& name) {
  const py::array a = as_array(array, name);
  if (!is_float(a)) throw InvalidInputError(name + ": expected float64 or float32 vertices, got " + dtype_of(a));
  require_columns(a, name, "(#V, 3)", 3);
  return double_matrix(a);
}

Eigen::MatrixXi faces_from(const py::handle& array, const std::string& name) {
  const py::array a = as_array(array, name);
  if (!is_int(a)) throw InvalidInputError(name + ": expected int32 or int64 faces, got " + dtype_of(a));
  require_columns(a, name, "(#F, 3)", 3);
  return int_matrix(a, name, "face");
}

Landmarks landmarks_from(const py::handle& array, int n_vertices_a, int n_vertices_b) {
  const py::array a = as_array(array, "landmarks");
  if (!is_int(a)) throw InvalidInputError("landmarks: expected int32 or int64 vertex indices, got " + dtype_of(a));
  require_columns(a, "landmarks", "(k, 2)", 2);
  const Eigen::MatrixXi L = int_matrix(a, "landmarks", "row");
  std::vector<std::array<long long, 2>> pairs(static_cast<size_t>(L.rows()));
  for (Eigen::Index i = 0; i < L.rows(); ++i) pairs[static_cast<size_t>(i)] = {L(i, 0), L(i, 1)};
  return make_landmarks(pairs, "landmarks", n_vertices_a, n_vertices_b);
}

std::vector<SurfacePoint> face_points_from(const py::handle& faces, const py::handle& barycentric, int n_faces) {
  const py::array f = as_array(faces, "faces");
  if (!is_int(f) || f.ndim() != 1) {
    throw InvalidInputError("faces: expected a 1-D int32 or int64 array, got " + dtype_of(f) + " of shape " +
                            shape_of(f));
  }
  const py::array b = as_array(barycentric, "barycentric");
  if (!is_float(b)) throw InvalidInputError("barycentric: expected float64 or float32, got " + dtype_of(b));
  require_columns(b, "barycentric", "(n, 3)", 3);
  if (b.shape(0) != f.shape(0)) {
    throw InvalidInputError("barycentric: " + std::to_string(b.shape(0)) + " rows, but faces has " +
                            std::to_string(f.shape(0)));
  }
  const auto face_array = py::array_t<std::int64_t, py::array::forcecast>::ensure(f);
  const auto face = face_array.unchecked<1>();
  const Eigen::MatrixXd B = double_matrix(b);
  std::vector<SurfacePoint> points;
  points.reserve(static_cast<size_t>(B.rows()));
  for (Eigen::Index i = 0; i < B.rows(); ++i) {
    const std::string row = "row " + std::to_string(i) + ": ";
    if (face(i) < 0 || face(i) >= n_faces) {
      throw InvalidInputError("faces: " + row + "face " + std::to_string(face(i)) + " is out of range (" +
                              std::to_string(n_faces) + " faces)");
    }
    if (!B.row(i).allFinite() || B.row(i).minCoeff() < -1e-12 || std::abs(B.row(i).sum() - 1) > 1e-9) {
      throw InvalidInputError("barycentric: " + row + "(" + figure(B(i, 0), 17) + ", " + figure(B(i, 1), 17) + ", " +
                              figure(B(i, 2), 17) + ") are not barycentric coordinates (>= 0, summing to 1)");
    }
    points.push_back(SurfacePoint::in_face(FaceId(static_cast<int>(face(i))), {B(i, 0), B(i, 1), B(i, 2)}));
  }
  return points;
}

Eigen::MatrixXd values_from(const py::handle& array, const std::string& name) {
  const py::array a = as_array(array, name);
  const char kind = a.dtype().kind();
  if ((kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b') || a.ndim() < 1 || a.ndim() > 2) {
    throw InvalidInputError(name + ": expected a numeric array of shape (n,) or (n, k), got " + dtype_of(a) +
                            " of shape " + shape_of(a));
  }
  if (a.ndim() == 2) return double_matrix(a);
  const auto typed = py::array_t<double, py::array::forcecast>::ensure(a);
  const auto x = typed.unchecked<1>();
  Eigen::MatrixXd M(x.shape(0), 1);
  for (py::ssize_t i = 0; i < x.shape(0); ++i) M(i, 0) = x(i);
  return M;
}

py::array_t<int> faces_of(const std::vector<SurfacePoint>& points) {
  py::array_t<int> out(static_cast<py::ssize_t>(points.size()));
  auto o = out.mutable_unchecked<1>();
  for (size_t i = 0; i < points.size(); ++i) o(static_cast<py::ssize_t>(i)) = points[i].face.idx;
  return out;
}

py::array_t<double> barycentric_of(const std::vector<SurfacePoint>& points) {
  py::array_t<double> out({static_cast<py::ssize_t>(points.size()), py::ssize_t{3}});
  auto o = out.mutable_unchecked<2>();
  for (size_t i = 0; i < points.size(); ++i) {
    for (size_t k = 0; k < 3; ++k) o(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(k)) = points[i].bary[k];
  }
  return out;
}

py::array_t<int> to_numpy(const std::vector<int>& v) {
  py::array_t<int> out(static_cast<py::ssize_t>(v.size()));
  auto o = out.mutable_unchecked<1>();
  for (size_t i = 0; i < v.size(); ++i) o(static_cast<py::ssize_t>(i)) = v[i];
  return out;
}

}  // namespace liftmap::python
