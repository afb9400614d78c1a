#include "map/write_map.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <utility>

#include "core/errors.h"
#include "core/parallel_for_each.h"
#include "cut/write_cut.h"
#include "io/output_file.h"
#include "io/text_line.h"
#include "io/vertex_map.h"
#include "io/write_mesh.h"
#include "map/overlay_files.h"
#include "map/write_figures.h"

namespace liftmap {

namespace {

nlohmann::json stats_json(const DistortionStats& s) {
  return {{"mean", s.mean}, {"median", s.median}, {"p95", s.p95}, {"max", s.max}};
}

}  // namespace

void write_barycentric_matrix(const std::string& path, const std::vector<SurfacePoint>& images,
                              const Eigen::MatrixXi& F_target) {
  OutputFile f(path);
  TextLine line;
  for (size_t i = 0; i < images.size(); ++i) {
    const SurfacePoint& p = images[i];
    for (int k = 0; k < 3; ++k) {
      if (p.bary[static_cast<size_t>(k)] != 0.0) {
        line.add(static_cast<long long>(i)).add(F_target(p.face.idx, k)).add(p.bary[static_cast<size_t>(k)]);
        line.write_to(f.get());
      }
    }
  }
  f.close();
}

std::vector<std::string> map_output_names() {
  std::vector<std::string> names = {"A_to_B.txt", "B_to_A.txt", "A_to_B.ijv", "B_to_A.ijv"};
  for (std::string& name : cut_output_names()) names.push_back(std::move(name));
  for (const char* name : {"cut_A_to_B.txt", "cut_B_to_A.txt", "render.png", "distortion.png", "A_textured.obj",
                           "A_textured.mtl", "B_textured.obj", "B_textured.mtl", "texture.png", "overlay.obj",
                           "overlay_points.txt", "overlay_faces.txt", "report.json"}) {
    names.emplace_back(name);
  }
  return names;
}

nlohmann::json map_report(const MapResult& map, const std::string& path_a, const TriangleMesh& a,
                          const std::string& path_b, const TriangleMesh& b, const Landmarks& landmarks,
                          const MapOptions& options) {
  nlohmann::json j;
  j["input"] = {
      {"A", {{"file", path_a}, {"vertices", a.V.rows()}, {"faces", a.F.rows()}}},
      {"B", {{"file", path_b}, {"vertices", b.V.rows()}, {"faces", b.F.rows()}}},
  };
  nlohmann::json lm = nlohmann::json::array();
  for (size_t i = 0; i < landmarks.a.size(); ++i) {
    const auto token = [](const SurfacePoint& p) {
      return p.kind == SurfacePoint::Kind::kVertex ? nlohmann::json(p.vertex.idx) : nlohmann::json(landmark_token(p));
    };
    lm.push_back({token(landmarks.a[i]), token(landmarks.b[i])});
  }
  j["landmarks"] = lm;
  j["options"] = {
      {"p", std::isinf(options.flatten.p) ? nlohmann::json("inf") : nlohmann::json(options.flatten.p)},
      {"h", options.flatten.h == DistortionCombiner::kNorm ? "eq3" : "eq2"},
      {"solver", uses_primal_dual(options.flatten) ? "primal-dual" : "barrier"},
      {"normalize_area", options.flatten.normalize_area},
      {"relative_tolerance", options.flatten.relative_tolerance},
      {"gap_fraction", options.flatten.gap_fraction},
      {"max_subproblem_gap", options.flatten.max_subproblem_gap},
      {"start_gap_fraction", options.flatten.start_gap_fraction},
      {"relaxed_start_gap_fraction", options.flatten.relaxed_start_gap_fraction},
      {"rotation_gain_start_fraction", options.flatten.rotation_gain_start_fraction},
      {"isotropic_anticonformal_curvature", options.flatten.solver.barrier.isotropic_anticonformal_curvature},
      {"max_iterations", options.flatten.max_iterations},
      {"start_relaxation_steps", options.flatten.joint_start.newton.max_iterations},
      {"tree", options.cut.tree == CutOptions::Tree::kPath ? "path" : "mst"},
      {"remesh", options.cut.remesh},
  };
  // How the process ran, which decides its speed, never the map: the OpenMP wait policy as libgomp read it (the
  // CLI makes it passive unless set).
  j["run"] = {
      {"openmp_wait_policy", std::getenv("OMP_WAIT_POLICY") != nullptr ? std::getenv("OMP_WAIT_POLICY") : "default"},
  };
  j["cut"] = {
      {"tree_edges", map.cut.tree},
      {"boundary_vertices", map.cut.nu.size()},
      {"disk_A", {{"vertices", map.disk_a.n_vertices()}, {"faces", map.disk_a.n_faces()}}},
      {"disk_B", {{"vertices", map.disk_b.n_vertices()}, {"faces", map.disk_b.n_faces()}}},
      {"path_lengths_A", map.cut.a.path_lengths},
      {"path_lengths_B", map.cut.b.path_lengths},
  };
  nlohmann::json it = nlohmann::json::array();
  for (const auto& i : map.flattening.iterations) {
    it.push_back(
        {{"energy", i.energy},
         {"energy_A", i.energy_m},
         {"energy_B", i.energy_n},
         {"max_distortion", i.max_distortion},
         {"min_area_ratio", i.min_area_ratio},
         {"subproblem_objective", i.subproblem_objective},
         {"newton_steps", i.newton_steps},
         {"subproblem_gap", i.subproblem_gap},
         {"subproblem_converged", i.subproblem_converged},
         {"stalled_centrings", i.stalled_centrings},
         {"subproblem_refined", i.subproblem_refined},
         {"subproblem_status", i.subproblem_status ? nlohmann::json(to_string(*i.subproblem_status)) : nullptr},
         {"seconds", i.seconds}});
  }
  nlohmann::json start = nlohmann::json::array();
  for (size_t k = 0; k < 2; ++k) {
    const auto& s = map.flattening.start[k];
    start.push_back({{"drift", s.drift},
                     {"drift_where_squeezed", s.local},
                     {"energy_before_optimization", s.energy},
                     {"min_area_ratio_before_optimization", s.min_area_ratio},
                     {"optimization_steps", map.flattening.start_steps[k]}});
  }
  const JointStartRelaxation& relax = map.flattening.joint_start;
  j["flatten"] = {{"start", start},
                  {"joint_start_relaxation",
                   {{"steps", relax.steps},
                    {"energy_before", relax.energy_before},
                    {"energy_after", relax.energy_after},
                    {"seconds", relax.seconds}}},
                  {"iterations", it},
                  {"converged", map.flattening.converged},
                  {"last_subproblem_steps", map.flattening.last_subproblem_steps},
                  {"stop_reason", map.flattening.stop_reason}};
  j["seconds"] = {{"cut", map.seconds.cut},         {"flatten", map.seconds.flatten}, {"lift", map.seconds.lift},
                  {"overlay", map.seconds.overlay}, {"verify", map.seconds.verify},   {"total", map.seconds.total}};
  j["distortion"] = {
      {"measure", "per face max(Sigma, 1/sigma), area-weighted, both meshes scaled to the same area"},
      {"Phi", stats_json(map.distortion_phi)},
      {"Psi", stats_json(map.distortion_psi)},
      {"f", stats_json(map.distortion_f)},
      {"g", stats_json(map.distortion_g)},
      {"f_g_method",
       "dense sampling: " + std::to_string(options.distortion_samples_per_edge * options.distortion_samples_per_edge) +
           " points per face (centroids of its sub-triangles), J = J_target^-1 J_source"},
  };
  const MapVerification& v = map.verification;
  j["verification"] = {{"passed", v.passed},
                       {"failures", v.failures},
                       {"min_orientation", v.min_orientation},
                       {"max_boundary_angle_sum", v.max_boundary_angle_sum},
                       {"lifting_residual", v.lifting_residual},
                       {"round_trip_error", v.round_trip_error},
                       {"landmark_error", v.landmark_error}};
  if (map.overlay.F.rows() > 0) {
    const OverlayCheck& c = v.overlay;
    j["overlay"] = {{"vertices", map.overlay.VA.rows()},
                    {"triangles", map.overlay.F.rows()},
                    {"area_error_A", c.area_error_a},
                    {"area_error_B", c.area_error_b},
                    {"max_face_area_error_A", c.face_area_error_a},
                    {"max_face_area_error_B", c.face_area_error_b},
                    {"uncovered_faces_A", c.uncovered_faces_a},
                    {"uncovered_faces_B", c.uncovered_faces_b},
                    {"flipped_triangles_A", c.flipped_a},
                    {"flipped_triangles_B", c.flipped_b},
                    {"rounding_level_triangles_A", c.degenerate_a},
                    {"rounding_level_triangles_B", c.degenerate_b},
                    {"vertex_error", v.overlay_vertex_error}};
  }
  return j;
}

std::vector<SurfacePoint> images_in_given_order(std::vector<SurfacePoint> images, bool target_reversed) {
  if (target_reversed) {
    for (SurfacePoint& p : images) std::swap(p.bary[1], p.bary[2]);
  }
  return images;
}

Landmarks landmarks_across_reversal(Landmarks landmarks, bool reversed_a, bool reversed_b) {
  landmarks.a = images_in_given_order(std::move(landmarks.a), reversed_a);
  landmarks.b = images_in_given_order(std::move(landmarks.b), reversed_b);
  return landmarks;
}

nlohmann::json map_report(const MapResult& map, const MapInputs& inputs, const MapOptions& options) {
  // The landmarks' tokens as in the file.
  const Landmarks given = landmarks_across_reversal(inputs.landmarks, inputs.reversed_a, inputs.reversed_b);
  nlohmann::json j = map_report(map, inputs.name_a, inputs.a, inputs.name_b, inputs.b, given, options);
  j["input"]["A"]["faces_reversed"] = inputs.reversed_a;
  j["input"]["B"]["faces_reversed"] = inputs.reversed_b;
  return j;
}

namespace {

/// Faces as in the input's file: before reverse_if_inside_out.
Eigen::MatrixXi faces_as_given(const TriangleMesh& mesh, bool reversed) {
  Eigen::MatrixXi F = mesh.F;
  if (reversed) F.col(1).swap(F.col(2));
  return F;
}

/// The overlay with its points' barycentric coordinates in the order of the inputs' faces as given.
Overlay overlay_in_given_order(Overlay o, const MapInputs& in) {
  o.on_a = images_in_given_order(std::move(o.on_a), in.reversed_a);
  o.on_b = images_in_given_order(std::move(o.on_b), in.reversed_b);
  return o;
}

/// The inputs as the files of a map from A onto B name them: source A, target B, faces as given.
MapMeshes input_meshes(const MapInputs& in) {
  return {mesh_fingerprint(in.a.V.rows(), faces_as_given(in.a, in.reversed_a)),
          mesh_fingerprint(in.b.V.rows(), faces_as_given(in.b, in.reversed_b))};
}

std::string in_folder(const std::string& dir, const std::string& name) {
  return (std::filesystem::path(dir) / name).string();
}

/// A_to_B.txt, B_to_A.txt and their .ijv matrices: faces and barycentric coordinates of the inputs as given.
/// \param a_onto_b input_meshes(in)
void write_input_maps(const std::string& dir, const MapResult& map, const MapInputs& in, const MapMeshes& a_onto_b) {
  const std::vector<SurfacePoint> a_to_b = images_in_given_order(map.a_to_b, in.reversed_b);
  const std::vector<SurfacePoint> b_to_a = images_in_given_order(map.b_to_a, in.reversed_a);
  write_vertex_map(in_folder(dir, "A_to_B.txt"), a_to_b, "liftmap map of A = " + in.name_a + " onto B = " + in.name_b,
                   a_onto_b);
  write_vertex_map(in_folder(dir, "B_to_A.txt"), b_to_a, "liftmap map of B = " + in.name_b + " onto A = " + in.name_a,
                   {a_onto_b.target, a_onto_b.source});
  write_barycentric_matrix(in_folder(dir, "A_to_B.ijv"), a_to_b, faces_as_given(in.b, in.reversed_b));
  write_barycentric_matrix(in_folder(dir, "B_to_A.ijv"), b_to_a, faces_as_given(in.a, in.reversed_a));
}

}  // namespace

void write_map_folder(const std::string& dir, const MapResult& map, const MapInputs& in, const nlohmann::json& report,
                      bool pictures, const std::function<void(const std::string&, const std::string&)>& progress) {
  const MapMeshes a_onto_b = input_meshes(in);
  // The data files, independent of one another, on the caller's threads: the largest (the overlay's) first.
  const std::vector<std::function<void()>> files = {
      [&] {
        if (map.overlay.F.rows() > 0) {
          write_overlay(in_folder(dir, "overlay.obj"), overlay_in_given_order(map.overlay, in), a_onto_b);
        }
      },
      [&] { write_textured_meshes(dir, map); },
      [&] { write_cut(dir, map.cut, map.flattening.Phi, map.flattening.Psi); },
      [&] { write_input_maps(dir, map, in, a_onto_b); },
      [&] {
        write_vertex_map(in_folder(dir, "cut_A_to_B.txt"), map.cut_a_to_b,
                         "per vt of cut_A.obj: face of cut_B.obj and barycentric coordinates");
      },
      [&] {
        write_vertex_map(in_folder(dir, "cut_B_to_A.txt"), map.cut_b_to_a,
                         "per vt of cut_B.obj: face of cut_A.obj and barycentric coordinates");
      },
  };
  const int n = static_cast<int>(files.size());
  parallel_for_each(n, n, [&](int i) { files[static_cast<size_t>(i)](); });
  if (pictures) {  // after the files: the rasteriser runs on the threads itself
    if (progress) progress("render", "render.png, distortion.png");
    write_map_render(in_folder(dir, "render.png"), map, in.a, in.b, in.landmarks.a, in.landmarks.b,
                     "A: " + std::filesystem::path(in.name_a).filename().string(),
                     "B: " + std::filesystem::path(in.name_b).filename().string());
    write_distortion_histogram(in_folder(dir, "distortion.png"), map);
  }
  // Last: a folder with a report.json holds every file of this run.
  OutputFile file(in_folder(dir, "report.json"));
  const std::string text = report.dump(2) + '\n';
  std::fputs(text.c_str(), file.get());
  file.close();
}

}  // namespace liftmap
