// `import liftmap`: the library's pipeline on numpy arrays. Every function is a thin wrapper over the library the
// CLI links; every C++ exception of core/errors.h becomes the liftmap exception of the same name, with its message.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <climits>
#include <nlohmann/json.hpp>
#include <string>

#include "arrays.h"
#include "batch_functions.h"
#include "check/check_mesh.h"
#include "core/errors.h"
#include "io/landmarks.h"
#include "io/read_mesh.h"
#include "map_function.h"
#include "map_object.h"

namespace py = pybind11;
using namespace pybind11::literals;

namespace liftmap::python {
namespace {

void register_exceptions(py::module_& m) {
  const py::object base = py::reinterpret_steal<py::object>(
      PyErr_NewExceptionWithDoc("liftmap.Error", "Base class of every liftmap error.", nullptr, nullptr));
  m.attr("Error") = base;
  auto with = [&](PyObject* builtin) { return py::make_tuple(base, py::handle(builtin)); };
  py::register_exception<IoError>(m, "ReadError", with(PyExc_OSError));
  py::register_exception<InvalidInputError>(m, "InvalidInputError", with(PyExc_ValueError));
  py::register_exception<UsageError>(m, "UsageError", with(PyExc_ValueError));
  py::register_exception<PipelineError>(m, "PipelineError", with(PyExc_RuntimeError));
  m.attr("ReadError").attr("__doc__") =
      "A file cannot be opened, read or parsed, or an output cannot be written (CLI exit code 3).";
  m.attr("InvalidInputError").attr("__doc__") =
      "Input that cannot be mapped: array shape or dtype, mesh (non-manifold, open, genus, NaN, index out of "
      "range), landmarks (CLI exit code 4). The message names the element.";
  m.attr("UsageError").attr("__doc__") = "An option value out of its range (CLI exit code 2).";
  m.attr("PipelineError").attr("__doc__") =
      "A pipeline stage failed on valid input: solver failure, failed verification (CLI exit code 5).";
}

py::tuple read_mesh_arrays(const std::string& path) {
  TriangleMesh mesh;
  {
    const py::gil_scoped_release unlocked;
    mesh = read_mesh(path);
  }
  return py::make_tuple(to_numpy(mesh.V), to_numpy(mesh.F));
}

py::array_t<int> read_landmark_pairs(const std::string& path, std::optional<int> n_a, std::optional<int> n_b) {
  const Landmarks lm = read_landmarks(path, n_a.value_or(INT_MAX), n_b.value_or(INT_MAX));
  Eigen::MatrixXi L(static_cast<Eigen::Index>(lm.a.size()), 2);
  for (size_t i = 0; i < lm.a.size(); ++i)
    L.row(static_cast<Eigen::Index>(i)) << lm.a[i].vertex.idx, lm.b[i].vertex.idx;  // vertex indices only
  return to_numpy(L);
}

py::dict read_surface_landmark_points(const std::string& path, const py::handle& VA, const py::handle& FA,
                                      const py::handle& VB, const py::handle& FB) {
  const Eigen::MatrixXd va = vertices_from(VA, "VA"), vb = vertices_from(VB, "VB");
  const Eigen::MatrixXi fa = faces_from(FA, "FA"), fb = faces_from(FB, "FB");
  require_face_corners(fa, va.rows(), "FA");
  require_face_corners(fb, vb.rows(), "FB");
  const Landmarks lm = [&] {
    const py::gil_scoped_release unlocked;
    return read_landmarks(path, va, fa, vb, fb);
  }();
  warn_landmarks(lm);
  return landmarks_dict(lm, fa, fb);
}

py::object check_arrays(const py::handle& V, const py::handle& F, const std::string& name) {
  const Eigen::MatrixXd Vm = vertices_from(V, "V");
  const Eigen::MatrixXi Fm = faces_from(F, "F");
  MeshReport report;
  {
    const py::gil_scoped_release unlocked;
    report = check_mesh(Vm, Fm);
  }
  return py::module_::import("json").attr("loads")(mesh_report_json(report, name).dump());
}

Map map_arrays(const py::handle& VA, const py::handle& FA, const py::handle& VB, const py::handle& FB,
               const py::handle& landmarks, const py::object& p, const std::string& h, bool normalize, double tolerance,
               int max_iterations, const std::string& solver, const std::string& tree, int samples,
               std::optional<int> threads, bool fix_orientation, const py::object& progress, const std::string& name_a,
               const std::string& name_b, bool accept_unverified, int start_relaxation, bool overlay) {
  MapKeywords k;
  k.arguments.choices = {norm_name(p), h, solver, tree};
  k.arguments.normalize = normalize;
  k.arguments.tolerance = tolerance;
  k.arguments.max_iterations = max_iterations;
  k.arguments.samples = samples;
  k.arguments.threads = threads;
  k.arguments.fix_orientation = fix_orientation;
  k.arguments.start_relaxation = start_relaxation;
  k.arguments.overlay = overlay;
  k.progress = progress;
  k.name_a = name_a;
  k.name_b = name_b;
  k.accept_unverified = accept_unverified;
  return compute_map(VA, FA, VB, FB, landmarks, k);
}

constexpr const char* kMapDoc = R"(map(VA, FA, VB, FB, landmarks, **options) -> Map

The continuous, bijective, low-distortion map between two closed genus-0 triangle meshes A and B with
corresponding landmarks (Aigerman, Poranne, Lipman 2014): the pipeline of `liftmap map`, verified.

Arrays: vertices float64 or float32, faces int32 or int64, C or Fortran order.
  VA: (#VA, 3) positions of A          FA: (#FA, 3) vertex indices of A, 0-based, counter-clockwise from outside
  VB: (#VB, 3) positions of B          FB: (#FB, 3) vertex indices of B
  landmarks: (k, 2) integer array, k >= 2: row i is a vertex of A and its partner on B; or landmarks anywhere on
    the surfaces, a dict of face points {"faces_A": (k,) int, "barycentric_A": (k, 3) float, "faces_B",
    "barycentric_B"} (barycentric coordinates in the order of the face's row of F, as read_surface_landmarks
    returns): checked as a landmark file's face points; one nearer to a side than 1e-3 of its face's height is moved
    onto it with a UserWarning.
Options (the CLI's, README "Command line"):
  p: 2 or "inf" (also 2.0, float("inf")): norm of the energy (10a). Default 2.
  h: "eq3" (sqrt(Sigma^2 + sigma^-2)) or "eq2" (max): per-face distortion. Default "eq3".
  normalize: scale both meshes to the same area (the CLI's --no-normalize is normalize=False). Default True.
  tolerance: stop when the energy improves by less than this, relative; finite > 0. Default 1e-3.
  max_iterations: outer iterations of the flattening, 0 to 10000. Default 10.
  solver: "auto" (barrier for p = 2, primal-dual for p = inf), "barrier" or "primal-dual". Default "auto".
  tree: cut tree, "mst" (paper) or "path" (through all landmarks). Default "mst".
  start_relaxation: Newton steps at most of the start's joint relaxation, common boundary free, 0 to 10000 (0:
    the paper's start on a circle, which takes more outer iterations). Default 300.
  overlay: compute the overlay (Map.overlay, overlay.obj) and check it in the verification (the CLI's
    --no-overlay is overlay=False). Default True.
  samples: n, the n^2 samples per face at which the distortion of f and g is measured, 1 to 10. Default 2.
  threads: threads of the per-face work, 1 to 4 per hardware thread; None: the calling thread's OpenMP
    setting. Set for this call on its own thread only.
  fix_orientation: reverse the faces of an inside-out mesh (negative signed volume) with a UserWarning instead of
    rejecting it; the map's faces and barycentric coordinates keep the vertex order given. Default False.
  progress: None or callable(stage: str, message: str), called as the pipeline advances (on the calling
    thread, with the GIL held; an exception it raises ends the call).
  name_a, name_b: how messages, the report and the saved files name A and B. Default "mesh A", "mesh B".
  accept_unverified: return a map whose verification failed (Map.verified is False) instead of raising.
The GIL is released while the pipeline runs: maps in several Python threads run in parallel.

Raises:
  InvalidInputError: an array of the wrong shape or dtype, a mesh that cannot be mapped (the message names the
    element: NaN coordinate, face index out of range, non-manifold edge, genus, ...), invalid landmarks (names
    the row: index out of range, vertex used twice, face or barycentric coordinates out of range, two landmarks at
    one point, fewer than 2 pairs).
  UsageError: an option out of its range (names the option).
  PipelineError: a stage failed, or the verification failed (unless accept_unverified).)";

void bind_vertex_map(py::module_& m) {
  py::class_<VertexMap>(m, "VertexMap",
                        "A map on the vertices of its source: per source vertex, a face of the target and "
                        "barycentric coordinates in the order of that face's vertices as given.")
      .def_property_readonly("faces", &VertexMap::faces, "(#V,) int32: a face of the target per source vertex.")
      .def_property_readonly("barycentric", &VertexMap::barycentric,
                             "(#V, 3) float64: barycentric coordinates in that face, each row summing to 1.")
      .def("points", &VertexMap::points, "points() -> (#V, 3) float64: the images' positions on the target.")
      .def(
          "__len__", [](const VertexMap& v) { return v.images.size(); }, "The number of source vertices.");
}

/// Binds the side-A and side-B properties of one Map accessor taking a Side.
template <typename Method>
void def_sides(py::class_<Map>& c, const char* name_a, const char* name_b, Method method, const char* doc_a,
               const char* doc_b) {
  c.def_property_readonly(
      name_a, [method](const Map& x) { return (x.*method)(Side::kA); }, doc_a);
  c.def_property_readonly(
      name_b, [method](const Map& x) { return (x.*method)(Side::kB); }, doc_b);
}

void bind_map(py::module_& m) {
  py::class_<Map> c(m, "Map", "The verified map between meshes A and B, made by liftmap.map.");
  def_sides(c, "a_to_b", "b_to_a", &Map::on_inputs,
            "VertexMap f: per vertex of A, a face of B and barycentric coordinates (A_to_B.txt).",
            "VertexMap g: per vertex of B, a face of A and barycentric coordinates (B_to_A.txt).");
  def_sides(c, "cut_a_to_b", "cut_b_to_a", &Map::on_cut,
            "VertexMap f on the cut mesh: per vertex of cut['A'] (vt of cut_A.obj), a face of cut['B']['F_cut'] "
            "(cut_A_to_B.txt).",
            "VertexMap g on the cut mesh: per vertex of cut['B'], a face of cut['A']['F_cut'] (cut_B_to_A.txt).");
  def_sides(c, "flattening_a", "flattening_b", &Map::flattening,
            "(#Vc_A, 2) float64: Phi, the flattening of A's cut mesh (vt of cut_A.obj).",
            "(#Vc_B, 2) float64: Psi, the flattening of B's cut mesh (vt of cut_B.obj).");
  c.def_property_readonly("cut", &Map::cut, R"(The cut as arrays: a dict with
  "A", "B": dicts of one side:
    "V" (#Vr, 3) float64, "F" (#Fr, 3) int32: the refined mesh (the cut paths run along its edges);
    "face_to_input" (#Fr,) int32: the input face holding each refined face;
    "V_cut" (#Vc, 3) float64, "F_cut" (#Fr, 3) int32: the cut mesh, a disk (face i is refined face i);
    "cut_to_refined" (#Vc,) int32: each cut vertex's refined vertex;
    "uv" (#Vc, 2) float64: its flattening (Phi for A, Psi for B);
    "landmarks" (k,) int32: each landmark's refined vertex;
    "paths": list of k - 1 int32 arrays, per tree edge the refined vertices from child to parent landmark;
  "tree" (k - 1, 2) int32: the tree edges {parent, child} as landmark indices;
  "boundary_map" (#nu, 2) int32: the boundary correspondence, cut vertices {of A, of B} (boundary_map.txt).)")
      .def_property_readonly("overlay", &Map::overlay, R"(The overlay (overlay.obj): the common refinement of A and B
under the map, which is affine on each of its triangles. A dict with
  "V_A", "V_B" (#Vo, 3) float64: each overlay vertex's position on A and on B;
  "F" (#Fo, 3) int32: triangles, counter-clockwise on both;
  "face_A", "face_B" (#Fo,) int32: the input face of A and of B holding each triangle;
  "faces_A", "barycentric_A" (#Vo,), (#Vo, 3): each vertex as a point of A (overlay_points.txt), likewise "faces_B",
  "barycentric_B" on B.
Empty arrays if the map was made with overlay=False.)")
      .def_property_readonly("report", &Map::report,
                             "report.json as a dict (sizes, options, timings, energies, "
                             "distortion, verification).")
      .def_property_readonly("verified", &Map::verified, "Whether the map passed its verification.")
      .def("evaluate", &Map::evaluate, "faces"_a, "barycentric"_a, "source"_a = "A",
           R"(evaluate(faces, barycentric, source="A") -> (faces, barycentric)

Images of arbitrary points of the source mesh ("A": f into B, "B": g into A).
  faces: (n,) int32 or int64 faces of the source; barycentric: (n, 3) float64 or float32 coordinates in the order
  of each face's vertices as given (>= 0, summing to 1).
Returns (n,) int32 faces and (n, 3) float64 barycentric coordinates of the other mesh.
Raises InvalidInputError naming the row for a face out of range or invalid coordinates.)")
      .def("transfer", &Map::transfer, "values"_a, "source"_a = "A",
           R"(transfer(values, source="A") -> array

Per-vertex values of the source mesh carried onto the other mesh's vertices: each vertex of B gets A's values
interpolated at its image g(w) (source "A"), or each vertex of A gets B's values at f(v) (source "B").
  values: (#V,) or (#V, k) numeric array, one row per vertex of the source.
Returns float64 of shape (#V_other,) or (#V_other, k).
Raises InvalidInputError if the rows do not match the source's vertices.)")
      .def("save", &Map::save, "dir"_a, "pictures"_a = true, R"(save(dir, pictures=True)

Writes the files of `liftmap map` into dir (created if missing; a previous run's files are removed first),
report.json last; with pictures=False (the CLI's --no-pictures) all but render.png and distortion.png, which take
about a second to draw. Raises ReadError if the folder cannot be written.)");
}

}  // namespace
}  // namespace liftmap::python

PYBIND11_MODULE(liftmap, m) {
  using namespace liftmap::python;
  m.doc() =
      "liftmap: continuous, bijective, low-distortion maps between two closed genus-0 triangle meshes from "
      "landmarks (Aigerman, Poranne, Lipman: Lifted Bijections for Low Distortion Surface Mappings, 2014).";
  register_exceptions(m);
  bind_batch(m);
  bind_vertex_map(m);
  bind_map(m);
  m.def("read_mesh", &read_mesh_arrays, "path"_a, R"(read_mesh(path) -> (V, F)

Reads a triangle mesh (.off, .obj, .ply, .stl): V (#V, 3) float64 positions, F (#F, 3) int32 vertex indices.
Raises ReadError naming the file and line or element.)");
  m.def("read_landmarks", &read_landmark_pairs, "path"_a, "n_vertices_a"_a = py::none(), "n_vertices_b"_a = py::none(),
        R"(read_landmarks(path, n_vertices_a=None, n_vertices_b=None) -> (k, 2) int32

Reads a landmark file of vertex pairs ('iA iB' per line, '#' comments); indices checked against the vertex counts
if given. A file with face points or 3D points: read_surface_landmarks.
Raises ReadError if the file cannot be read, InvalidInputError naming the file and line otherwise.)");
  m.def("read_surface_landmarks", &read_surface_landmark_points, "path"_a, "VA"_a, "FA"_a, "VB"_a, "FB"_a,
        R"(read_surface_landmarks(path, VA, FA, VB, FB) -> dict

Reads a landmark file with every token form of the CLI (README, "Landmarks"): vertex indices, face points
'f<face>:<b0>,<b1>,<b2>' and 3D points 'x,y,z' (located at the nearest surface point), checked against the meshes.
Returns the dict that map() takes as landmarks: "faces_A" (k,) int32, "barycentric_A" (k, 3) float64 in the order of
the face's row of FA, "faces_B", "barycentric_B"; a vertex landmark is a corner of its first face, coordinate 1.
A point moved onto a side of its face, or a 3D point far from the surface, gives a UserWarning naming the line.
Raises ReadError if the file cannot be read, InvalidInputError naming the file and line otherwise.)");
  m.def("check", &check_arrays, "V"_a, "F"_a, "name"_a = "mesh", R"(check(V, F, name="mesh") -> dict

Validates a mesh as `liftmap check --json` does: V (#V, 3) float64 or float32, F (#F, 3) int32 or int64. Returns
a dict with "mesh" (name), counts ("vertices", "faces", "edges", "connected_components", "boundary_edges",
"boundary_loops", "euler_characteristic", "genus"; None where undefined), "mappable" (bool) and "problems": a list
of {"kind", "count", "examples"}, each example naming the element.
Raises InvalidInputError only for an array of the wrong shape or dtype.)");
  m.def("map", &map_arrays, "VA"_a, "FA"_a, "VB"_a, "FB"_a, "landmarks"_a, py::kw_only(), "p"_a = 2, "h"_a = "eq3",
        "normalize"_a = true, "tolerance"_a = 1e-3, "max_iterations"_a = 10, "solver"_a = "auto", "tree"_a = "mst",
        "samples"_a = 2, "threads"_a = py::none(), "fix_orientation"_a = false, "progress"_a = py::none(),
        "name_a"_a = "mesh A", "name_b"_a = "mesh B", "accept_unverified"_a = false,
        "start_relaxation"_a = liftmap::JointStartRelaxationOptions{}.newton.max_iterations, "overlay"_a = true,
        kMapDoc);
}
