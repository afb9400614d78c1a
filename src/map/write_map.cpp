#include "map/write_map.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "core/errors.h"
#include "cut/write_cut.h"
#include "io/output_file.h"
#include "io/write_mesh.h"

namespace liftmap {

namespace {

nlohmann::json stats_json(const DistortionStats& s) {
  return {{"mean", s.mean}, {"median", s.median}, {"p95", s.p95}, {"max", s.max}};
}

}  // namespace

void write_barycentric_matrix(const std::string& path, const std::vector<SurfacePoint>& images,
                              const Eigen::MatrixXi& F_target) {
  OutputFile f(path);
  for (size_t i = 0; i < images.size(); ++i) {
    const SurfacePoint& p = images[i];
    for (int k = 0; k < 3; ++k) {
      if (p.bary[static_cast<size_t>(k)] != 0.0) {
        std::fprintf(f.get(), "%zu %d %.17g\n", i, F_target(p.face.idx, k), p.bary[static_cast<size_t>(k)]);
      }
    }
  }
  f.close();
}

std::vector<std::string> map_output_names() {
  std::vector<std::string> names = {"A_to_B.txt", "B_to_A.txt", "A_to_B.ijv", "B_to_A.ijv"};
  for (std::string& name : cut_output_names()) names.push_back(std::move(name));
  for (const char* name : {"cut_A_to_B.txt", "cut_B_to_A.txt", "render.png", "distortion.png", "A_textured.obj",
                           "A_textured.mtl", "B_textured.obj", "B_textured.mtl", "texture.png", "report.json"}) {
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
  for (size_t i = 0; i < landmarks.a.size(); ++i) lm.push_back({landmarks.a[i].idx, landmarks.b[i].idx});
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
      {"isotropic_anticonformal_curvature", options.flatten.solver.barrier.isotropic_anticonformal_curvature},
      {"max_iterations", options.flatten.max_iterations},
      {"tree", options.cut.tree == CutOptions::Tree::kPath ? "path" : "mst"},
      {"remesh", options.cut.remesh},
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
  j["flatten"] = {{"start", start},
                  {"iterations", it},
                  {"converged", map.flattening.converged},
                  {"stop_reason", map.flattening.stop_reason}};
  j["seconds"] = {{"cut", map.seconds.cut},
                  {"flatten", map.seconds.flatten},
                  {"lift", map.seconds.lift},
                  {"verify", map.seconds.verify},
                  {"total", map.seconds.total}};
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
  return j;
}

}  // namespace liftmap
