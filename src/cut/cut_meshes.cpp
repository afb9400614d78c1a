#include "cut/cut_meshes.h"

#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <unordered_set>

#include "core/errors.h"
#include "cut/boundary_correspondence.h"
#include "cut/cut_to_disk.h"
#include "cut/cut_tree.h"
#include "cut/edge_key.h"
#include "cut/geodesic_distance.h"
#include "cut/refined_mesh.h"
#include "cut/remesh_along_paths.h"
#include "cut/trace_cut_paths.h"

namespace liftmap {

namespace {

void check_input(const Mesh& mesh, const Eigen::MatrixXd& V, const std::vector<VertexId>& landmarks, const char* name) {
  if (!mesh.boundary_loops().empty() || mesh.euler_characteristic() != 2) {
    throw InvalidInputError(std::string("cut: mesh ") + name +
                            " is not a closed genus-0 surface (Euler characteristic " +
                            std::to_string(mesh.euler_characteristic()) + ", " +
                            std::to_string(mesh.boundary_loops().size()) + " boundary loops)");
  }
  std::map<int, size_t> seen;  // vertex -> first landmark on it
  for (size_t i = 0; i < landmarks.size(); ++i) {
    const int v = landmarks[i].idx;
    if (v < 0 || v >= mesh.n_vertices() || mesh.is_isolated(landmarks[i])) {
      throw InvalidInputError(std::string("cut: landmark ") + std::to_string(i) + " of mesh " + name + " is vertex " +
                              std::to_string(v) + ", which is not a vertex of a face");
    }
    const auto [it, fresh] = seen.emplace(v, i);
    if (!fresh) {
      throw InvalidInputError(std::string("cut: landmarks ") + std::to_string(it->second) + " and " +
                              std::to_string(i) + " of mesh " + name + " are on the same vertex " + std::to_string(v) +
                              " (each landmark needs its own vertex)");
    }
  }
  const auto dist = edge_graph_distances(mesh, V, landmarks[0]);
  for (size_t v = 0; v < dist.size(); ++v) {
    if (!mesh.is_isolated(VertexId(static_cast<int>(v))) && !std::isfinite(dist[v])) {
      throw InvalidInputError(std::string("cut: mesh ") + name + " is not connected (vertex " + std::to_string(v) +
                              " cannot be reached from landmark 0)");
    }
  }
}

CutSide finish(const RefinedMesh& r, const Mesh& input, const std::vector<int>& landmarks,
               std::vector<std::vector<int>> paths, CutDisk& disk) {
  CutSide side;
  side.V = r.vertex_matrix();
  side.F = r.face_matrix();
  side.on_input.reserve(r.on_input.size());
  for (const auto& p : r.on_input) side.on_input.push_back(as_face_point(input, p));
  side.face_to_input = Eigen::Map<const Eigen::VectorXi>(r.input_face.data(), static_cast<int>(r.input_face.size()));
  std::unordered_set<std::uint64_t> keys;
  for (const auto& p : paths) {
    for (size_t i = 0; i + 1 < p.size(); ++i) keys.insert(edge_key(p[i], p[i + 1]));
  }
  std::vector<char> is_cut(static_cast<size_t>(r.mesh.n_edges()), 0);
  for (int e = 0; e < r.mesh.n_edges(); ++e) {
    const HalfedgeId h = Mesh::halfedge(EdgeId(e));
    is_cut[static_cast<size_t>(e)] = keys.count(edge_key(r.mesh.tail(h).idx, r.mesh.head(h).idx)) ? 1 : 0;
  }
  disk = cut_to_disk(r.mesh, is_cut);
  side.F_cut = disk.F;
  side.cut_to_refined = disk.to_refined;
  side.landmarks = landmarks;
  for (const auto& p : paths) {
    double l = 0;
    for (size_t i = 0; i + 1 < p.size(); ++i) l += (side.V.row(p[i + 1]) - side.V.row(p[i])).norm();
    side.path_lengths.push_back(l);
  }
  side.paths = std::move(paths);
  return side;
}

}  // namespace

CutResult cut_meshes(const Eigen::MatrixXd& VA, const Eigen::MatrixXi& FA, const Eigen::MatrixXd& VB,
                     const Eigen::MatrixXi& FB, const std::vector<VertexId>& landmarks_a,
                     const std::vector<VertexId>& landmarks_b, const CutOptions& options) {
  if (landmarks_a.size() != landmarks_b.size()) {
    throw InvalidInputError("cut: " + std::to_string(landmarks_a.size()) + " landmarks on mesh A but " +
                            std::to_string(landmarks_b.size()) + " on mesh B");
  }
  if (landmarks_a.size() < 2) throw InvalidInputError("cut: at least 2 landmark pairs are needed");
  const Mesh mesh_a(FA, static_cast<int>(VA.rows()));
  const Mesh mesh_b(FB, static_cast<int>(VB.rows()));
  check_input(mesh_a, VA, landmarks_a, "A");
  check_input(mesh_b, VB, landmarks_b, "B");

  const Eigen::MatrixXd W = landmark_distances(mesh_a, VA, landmarks_a) + landmark_distances(mesh_b, VB, landmarks_b);
  CutResult result;
  result.tree = options.tree == CutOptions::Tree::kPath ? path_tree(W) : minimum_spanning_tree(W);

  RefinedMesh ra = make_refined_mesh(mesh_a, VA);
  RefinedMesh rb = make_refined_mesh(mesh_b, VB);
  std::vector<int> la, lb;
  for (const VertexId v : landmarks_a) la.push_back(v.idx);
  for (const VertexId v : landmarks_b) lb.push_back(v.idx);
  TraceOptions trace;
  trace.steiner = options.geodesic_paths;
  trace.shorten = options.geodesic_paths;
  TracedPaths traced = trace_cut_paths(ra, mesh_a, la, rb, mesh_b, lb, result.tree, trace);
  // The paths straight across input faces and the vertices of intermediate paths gone before the two sides'
  // vertices are paired, then the faces that the paired vertices split re-triangulated once more.
  if (options.remesh) {
    remesh_along_paths(ra, mesh_a, traced.paths_a, true);
    remesh_along_paths(rb, mesh_b, traced.paths_b, true);
  }
  equalize_paths(ra, mesh_a, traced.paths_a, rb, mesh_b, traced.paths_b, options.snap);
  if (options.remesh) {
    remesh_along_paths(ra, mesh_a, traced.paths_a);
    remesh_along_paths(rb, mesh_b, traced.paths_b);
  }

  CutDisk disk_a, disk_b;
  result.a = finish(ra, mesh_a, la, std::move(traced.paths_a), disk_a);
  result.b = finish(rb, mesh_b, lb, std::move(traced.paths_b), disk_b);
  const Mesh cut_a(disk_a.F, static_cast<int>(disk_a.to_refined.size()));
  const Mesh cut_b(disk_b.F, static_cast<int>(disk_b.to_refined.size()));
  result.nu = match_boundaries({&cut_a, &disk_a.to_refined, &la, &result.a.paths},
                               {&cut_b, &disk_b.to_refined, &lb, &result.b.paths});
  return result;
}

}  // namespace liftmap
