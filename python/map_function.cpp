#include "map_function.h"

#include <cmath>
#include <memory>

#include "arrays.h"
#include "check/check_mesh.h"
#include "core/errors.h"
#include "map/write_map.h"

namespace py = pybind11;

namespace liftmap::python {

namespace {

/// The callback called with the GIL held; the Python object is released with the GIL held too, whichever thread
/// drops the last copy of the std::function.
std::function<void(const std::string&, const std::string&)> progress_from(const py::object& callback) {
  if (callback.is_none()) return {};
  if (!PyCallable_Check(callback.ptr())) throw UsageError("progress: expected a callable(stage, message) or None");
  const std::shared_ptr<py::object> held(new py::object(callback), [](py::object* o) {
    const py::gil_scoped_acquire locked;
    delete o;
  });
  return [held](const std::string& stage, const std::string& message) {
    const py::gil_scoped_acquire locked;
    (*held)(stage, message);
  };
}

/// reverse_if_inside_out with the CLI's warning, as a Python UserWarning.
bool fix_orientation(TriangleMesh& mesh, const std::string& name) {
  const std::optional<double> volume = reverse_if_inside_out(mesh.V, mesh.F);
  if (!volume) return false;
  const std::string message = name + " is inside-out (signed volume " + figure(*volume) +
                              "): its faces are reversed (fix_orientation); maps into it keep the vertex order given";
  if (PyErr_WarnEx(PyExc_UserWarning, message.c_str(), 2) != 0) throw py::error_already_set();
  return true;
}

}  // namespace

std::string norm_name(const py::handle& p) {
  if (py::isinstance<py::str>(p)) return p.cast<std::string>();
  if (py::isinstance<py::int_>(p) || py::isinstance<py::float_>(p)) {
    const double x = p.cast<double>();
    if (x == 2) return "2";
    if (std::isinf(x) && x > 0) return "inf";
  }
  return py::repr(p).cast<std::string>();
}

MapOptions options_from(const MapKeywords& k) {
  MapOptions o = map_options(k.arguments);
  o.name_a = k.name_a;
  o.name_b = k.name_b;
  o.progress = progress_from(k.progress);
  return o;
}

Map compute_map(const py::handle& VA, const py::handle& FA, const py::handle& VB, const py::handle& FB,
                const py::handle& landmarks, const MapKeywords& keywords) {
  MapOptions options = options_from(keywords);
  auto state = std::make_shared<MapState>();
  state->given_a = {vertices_from(VA, "VA"), faces_from(FA, "FA")};
  state->given_b = {vertices_from(VB, "VB"), faces_from(FB, "FB")};
  MapInputs& in = state->inputs;
  in = {keywords.name_a, keywords.name_b, state->given_a, state->given_b, {}, false, false};
  in.landmarks = landmarks_from(landmarks, in.a.V, in.a.F, in.b.V, in.b.F);
  warn_landmarks(in.landmarks);
  if (keywords.arguments.fix_orientation) {
    in.reversed_a = fix_orientation(in.a, keywords.name_a);
    in.reversed_b = fix_orientation(in.b, keywords.name_b);
    in.landmarks = landmarks_across_reversal(std::move(in.landmarks), in.reversed_a, in.reversed_b);
  }
  {
    const py::gil_scoped_release unlocked;
    state->result = map_meshes(in.a.V, in.a.F, in.b.V, in.b.F, in.landmarks.a, in.landmarks.b, options);
  }
  options.progress = nullptr;
  state->options = options;
  state->report = map_report(state->result, in, options);
  state->disk_a = {state->result.disk_va, state->result.cut.a.F_cut};
  state->disk_b = {state->result.disk_vb, state->result.cut.b.F_cut};
  const MapVerification& v = state->result.verification;
  if (!v.passed && !keywords.accept_unverified) throw PipelineError("verification failed: " + v.failures.front());
  return Map(state);
}

}  // namespace liftmap::python
