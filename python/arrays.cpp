#include "arrays.h"

#include <array>
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

void require_face_corners(const Eigen::MatrixXi& F, Eigen::Index n_vertices, const std::string& name) {
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      if (F(f, k) < 0 || F(f, k) >= n_vertices) {
        throw InvalidInputError(name + ": face " + std::to_string(f) + " has vertex index " + std::to_string(F(f, k)) +
                                ", out of range (" + std::to_string(n_vertices) + " vertices)");
      }
    }
  }
}

Landmarks landmarks_from(const py::handle& landmarks, const Eigen::MatrixXd& VA, const Eigen::MatrixXi& FA,
                         const Eigen::MatrixXd& VB, const Eigen::MatrixXi& FB) {
  if (!py::isinstance<py::dict>(landmarks)) {
    return landmarks_from(landmarks, static_cast<int>(VA.rows()), static_cast<int>(VB.rows()));
  }
  const auto d = py::reinterpret_borrow<py::dict>(landmarks);
  for (const auto& item : d) {
    const auto key = py::str(item.first).cast<std::string>();
    if (key != "faces_A" && key != "barycentric_A" && key != "faces_B" && key != "barycentric_B") {
      throw InvalidInputError("landmarks: unknown key '" + key +
                              "' (expected faces_A, barycentric_A, faces_B, barycentric_B)");
    }
  }
  // Face points are placed on the faces before check_mesh has run (in map_meshes): their corners must exist.
  require_face_corners(FA, VA.rows(), "FA");
  require_face_corners(FB, VB.rows(), "FB");
  const auto points = [&](const std::string& side, int n_faces) {
    const std::string faces = "faces_" + side, barycentric = "barycentric_" + side;
    if (!d.contains(faces) || !d.contains(barycentric)) {
      throw InvalidInputError("landmarks: the dict has no '" + (d.contains(faces) ? barycentric : faces) +
                              "' (expected faces_A, barycentric_A, faces_B, barycentric_B)");
    }
    // The coordinates are checked by make_landmarks, as a landmark file's are: one rule for both.
    return face_points_from(d[faces.c_str()], d[barycentric.c_str()], n_faces, "landmarks['" + faces + "']",
                            "landmarks['" + barycentric + "']", CoordinateCheck::kLeaveToCaller);
  };
  return make_landmarks(points("A", static_cast<int>(FA.rows())), points("B", static_cast<int>(FB.rows())), "landmarks",
                        VA, FA, VB, FB);
}

py::dict landmarks_dict(const Landmarks& landmarks, const Eigen::MatrixXi& FA, const Eigen::MatrixXi& FB) {
  const auto as_face_points = [](std::vector<SurfacePoint> points, const Eigen::MatrixXi& F) {
    for (SurfacePoint& p : points) {
      if (p.kind != SurfacePoint::Kind::kVertex) continue;
      for (Eigen::Index f = 0; f < F.rows(); ++f) {
        for (int k = 0; k < 3; ++k) {
          if (F(f, k) != p.vertex.idx) continue;
          std::array<double, 3> b{0, 0, 0};
          b[static_cast<size_t>(k)] = 1;
          p = SurfacePoint::in_face(FaceId(static_cast<int>(f)), b);
          break;
        }
        if (p.kind == SurfacePoint::Kind::kFace) break;
      }
      if (p.kind != SurfacePoint::Kind::kFace) {
        throw InvalidInputError("landmark vertex " + std::to_string(p.vertex.idx) + " is on no face");
      }
    }
    return points;
  };
  const std::vector<SurfacePoint> a = as_face_points(landmarks.a, FA), b = as_face_points(landmarks.b, FB);
  py::dict d;
  d["faces_A"] = faces_of(a);
  d["barycentric_A"] = barycentric_of(a);
  d["faces_B"] = faces_of(b);
  d["barycentric_B"] = barycentric_of(b);
  return d;
}

void warn_landmarks(const Landmarks& landmarks) {
  for (const std::string& w : landmarks.warnings) {
    if (PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 2) != 0) throw py::error_already_set();
  }
}

std::vector<SurfacePoint> face_points_from(const py::handle& faces, const py::handle& barycentric, int n_faces,
                                           const std::string& faces_name, const std::string& barycentric_name,
                                           CoordinateCheck check) {
  const py::array f = as_array(faces, faces_name);
  if (!is_int(f) || f.ndim() != 1) {
    throw InvalidInputError(faces_name + ": expected a 1-D int32 or int64 array, got " + dtype_of(f) + " of shape " +
                            shape_of(f));
  }
  const py::array b = as_array(barycentric, barycentric_name);
  if (!is_float(b)) throw InvalidInputError(barycentric_name + ": expected float64 or float32, got " + dtype_of(b));
  require_columns(b, barycentric_name, "(n, 3)", 3);
  if (b.shape(0) != f.shape(0)) {
    throw InvalidInputError(barycentric_name + ": " + std::to_string(b.shape(0)) + " rows, but " + faces_name +
                            " has " + std::to_string(f.shape(0)));
  }
  const auto face_array = py::array_t<std::int64_t, py::array::forcecast>::ensure(f);
  const auto face = face_array.unchecked<1>();
  const Eigen::MatrixXd B = double_matrix(b);
  std::vector<SurfacePoint> points;
  points.reserve(static_cast<size_t>(B.rows()));
  for (Eigen::Index i = 0; i < B.rows(); ++i) {
    const std::string row = "row " + std::to_string(i) + ": ";
    if (face(i) < 0 || face(i) >= n_faces) {
      throw InvalidInputError(faces_name + ": " + row + "face " + std::to_string(face(i)) + " is out of range (" +
                              std::to_string(n_faces) + " faces)");
    }
    const bool barycentric_row =
        B.row(i).allFinite() && B.row(i).minCoeff() >= -1e-12 && std::abs(B.row(i).sum() - 1) <= 1e-9;
    if (check == CoordinateCheck::kStrict && !barycentric_row) {
      throw InvalidInputError(barycentric_name + ": " + row + "(" + figure(B(i, 0), 17) + ", " + figure(B(i, 1), 17) +
                              ", " + figure(B(i, 2), 17) + ") are not barycentric coordinates (>= 0, summing to 1)");
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
