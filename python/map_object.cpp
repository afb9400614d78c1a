#include "map_object.h"

#include "arrays.h"
#include "core/errors.h"
#include "io/output_folder.h"
#include "map/transfer.h"

namespace py = pybind11;

namespace liftmap::python {

namespace {

py::array_t<double> column_or_matrix(const Eigen::MatrixXd& M, bool column) {
  if (!column) return to_numpy(M);
  py::array_t<double> out(M.rows());
  auto o = out.mutable_unchecked<1>();
  for (Eigen::Index i = 0; i < M.rows(); ++i) o(i) = M(i, 0);
  return out;
}

}  // namespace

Side side_named(const std::string& value, const std::string& name) {
  if (value == "A") return Side::kA;
  if (value == "B") return Side::kB;
  throw UsageError(name + ": '" + value + "' is not one of A, B");
}

py::array_t<int> VertexMap::faces() const { return faces_of(images); }

py::array_t<double> VertexMap::barycentric() const { return barycentric_of(images); }

py::array_t<double> VertexMap::points() const { return to_numpy(interpolate_at(target->F, target->V, images)); }

VertexMap Map::on_inputs(Side side) const {
  const MapState& s = *state_;
  if (side == Side::kA) {
    return {images_in_given_order(s.result.a_to_b, s.inputs.reversed_b), {state_, &s.given_b}};
  }
  return {images_in_given_order(s.result.b_to_a, s.inputs.reversed_a), {state_, &s.given_a}};
}

VertexMap Map::on_cut(Side side) const {
  const MapState& s = *state_;
  if (side == Side::kA) return {s.result.cut_a_to_b, {state_, &s.disk_b}};
  return {s.result.cut_b_to_a, {state_, &s.disk_a}};
}

py::tuple Map::evaluate(const py::handle& faces, const py::handle& barycentric, const std::string& source) const {
  const Side side = side_named(source, "source");
  const MapState& s = *state_;
  const bool from_a = side == Side::kA;
  const bool source_reversed = from_a ? s.inputs.reversed_a : s.inputs.reversed_b;
  const bool target_reversed = from_a ? s.inputs.reversed_b : s.inputs.reversed_a;
  const auto n_faces = static_cast<int>((from_a ? s.given_a : s.given_b).F.rows());
  // Swapping coordinates 1 and 2 of a reversed mesh's face points converts between its faces as given and as mapped.
  std::vector<SurfacePoint> points =
      images_in_given_order(face_points_from(faces, barycentric, n_faces), source_reversed);
  {
    py::gil_scoped_release unlocked;
    for (SurfacePoint& p : points) p = evaluate_map(s.result, side, p);
  }
  points = images_in_given_order(std::move(points), target_reversed);
  return py::make_tuple(faces_of(points), barycentric_of(points));
}

py::array_t<double> Map::transfer(const py::handle& values, const std::string& source) const {
  const Side side = side_named(source, "source");
  const MapState& s = *state_;
  const TriangleMesh& from = side == Side::kA ? s.inputs.a : s.inputs.b;
  const Eigen::MatrixXd X = values_from(values, "values");
  if (X.rows() != from.V.rows()) {
    throw InvalidInputError("values: " + std::to_string(X.rows()) + " rows, but mesh " + source + " has " +
                            std::to_string(from.V.rows()) + " vertices");
  }
  // The other mesh's vertices, located on the source: g for values of A, f for values of B.
  const std::vector<SurfacePoint>& located = side == Side::kA ? s.result.b_to_a : s.result.a_to_b;
  Eigen::MatrixXd out;
  {
    py::gil_scoped_release unlocked;
    out = interpolate_at(from.F, X, located);
  }
  return column_or_matrix(out, py::array::ensure(values).ndim() == 1);
}

py::array_t<double> Map::flattening(Side side) const {
  return to_numpy(side == Side::kA ? state_->result.flattening.Phi : state_->result.flattening.Psi);
}

namespace {

py::dict cut_side(const CutSide& c, const TriangleMesh& disk, const Eigen::MatrixXd& uv) {
  py::dict d;
  d["V"] = to_numpy(c.V);
  d["F"] = to_numpy(c.F);
  d["face_to_input"] = to_numpy(std::vector<int>(c.face_to_input.begin(), c.face_to_input.end()));
  d["V_cut"] = to_numpy(disk.V);
  d["F_cut"] = to_numpy(c.F_cut);
  d["cut_to_refined"] = to_numpy(std::vector<int>(c.cut_to_refined.begin(), c.cut_to_refined.end()));
  d["uv"] = to_numpy(uv);
  d["landmarks"] = to_numpy(c.landmarks);
  py::list paths;
  for (const std::vector<int>& p : c.paths) paths.append(to_numpy(p));
  d["paths"] = paths;
  return d;
}

py::array_t<int> pairs(const std::vector<std::array<int, 2>>& p) {
  Eigen::MatrixXi M(static_cast<Eigen::Index>(p.size()), 2);
  for (size_t i = 0; i < p.size(); ++i) M.row(static_cast<Eigen::Index>(i)) << p[i][0], p[i][1];
  return to_numpy(M);
}

}  // namespace

py::dict Map::cut() const {
  const MapState& s = *state_;
  py::dict d;
  d["A"] = cut_side(s.result.cut.a, s.disk_a, s.result.flattening.Phi);
  d["B"] = cut_side(s.result.cut.b, s.disk_b, s.result.flattening.Psi);
  d["tree"] = pairs(s.result.cut.tree);
  d["boundary_map"] = pairs(s.result.cut.nu);
  return d;
}

py::dict Map::overlay() const {
  const MapState& s = *state_;
  const Overlay& o = s.result.overlay;
  py::dict d;
  d["V_A"] = to_numpy(o.VA);
  d["V_B"] = to_numpy(o.VB);
  d["F"] = to_numpy(o.F);
  d["face_A"] = to_numpy(std::vector<int>(o.face_a.begin(), o.face_a.end()));
  d["face_B"] = to_numpy(std::vector<int>(o.face_b.begin(), o.face_b.end()));
  const auto on_a = images_in_given_order(o.on_a, s.inputs.reversed_a);
  const auto on_b = images_in_given_order(o.on_b, s.inputs.reversed_b);
  d["faces_A"] = faces_of(on_a);
  d["barycentric_A"] = barycentric_of(on_a);
  d["faces_B"] = faces_of(on_b);
  d["barycentric_B"] = barycentric_of(on_b);
  return d;
}

py::object Map::report() const { return py::module_::import("json").attr("loads")(state_->report.dump()); }

void Map::save(const std::string& dir, bool pictures) const {
  const MapState& s = *state_;
  py::gil_scoped_release unlocked;
  prepare_output_folder(dir, map_output_names(), {});
  write_map_folder(dir, s.result, s.inputs, s.report, pictures);
}

}  // namespace liftmap::python
