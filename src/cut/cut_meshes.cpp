#include "cut/cut_meshes.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <unordered_set>

#include "core/errors.h"
#include "core/parallel_for_each.h"
#include "cut/boundary_correspondence.h"
#include "cut/cut_to_disk.h"
#include "cut/cut_tree.h"
#include "cut/edge_key.h"
#include "cut/geodesic_distance.h"
#include "cut/insert_landmarks.h"
#include "cut/refined_mesh.h"
#include "cut/remesh_along_paths.h"
#include "cut/trace_cut_paths.h"

namespace liftmap {

namespace {

/// Why `p` is not a point of `mesh` with at least one face around it, or empty if it is.
std::string invalid_point(const Mesh& mesh, const SurfacePoint& p) {
  switch (p.kind) {
    case SurfacePoint::Kind::kVertex:
      if (p.vertex.idx < 0 || p.vertex.idx >= mesh.n_vertices() || mesh.is_isolated(p.vertex)) {
        return "vertex " + std::to_string(p.vertex.idx) + ", which is not a vertex of a face";
      }
      return {};
    case SurfacePoint::Kind::kEdge:
      if (p.edge.idx < 0 || p.edge.idx >= mesh.n_edges())
        return "on edge " + std::to_string(p.edge.idx) + ", out of range";
      if (!(p.t > 0 && p.t < 1)) return "on edge " + std::to_string(p.edge.idx) + " at t = " + std::to_string(p.t);
      return {};
    case SurfacePoint::Kind::kFace: {
      if (p.face.idx < 0 || p.face.idx >= mesh.n_faces())
        return "in face " + std::to_string(p.face.idx) + ", out of range";
      double sum = 0;
      for (const double b : p.bary) {
        if (!std::isfinite(b) || b < 0)
          return "in face " + std::to_string(p.face.idx) + " with a coordinate " + std::to_string(b);
        sum += b;
      }
      if (std::abs(sum - 1) > 1e-9)
        return "in face " + std::to_string(p.face.idx) + " with coordinates summing to " + std::to_string(sum);
      return {};
    }
  }
  return {};
}

/// A vertex of the element of `p` (where a search from it can start).
VertexId some_vertex(const Mesh& mesh, const SurfacePoint& p) {
  switch (p.kind) {
    case SurfacePoint::Kind::kVertex:
      return p.vertex;
    case SurfacePoint::Kind::kEdge:
      return mesh.tail(Mesh::halfedge(p.edge));
    case SurfacePoint::Kind::kFace:
      return mesh.face_vertices(p.face)[0];
  }
  return p.vertex;
}

void check_input(const Mesh& mesh, const Eigen::MatrixXd& V, const std::vector<SurfacePoint>& landmarks,
                 const char* name) {
  if (!mesh.boundary_loops().empty() || mesh.euler_characteristic() != 2) {
    throw InvalidInputError(std::string("cut: mesh ") + name +
                            " is not a closed genus-0 surface (Euler characteristic " +
                            std::to_string(mesh.euler_characteristic()) + ", " +
                            std::to_string(mesh.boundary_loops().size()) + " boundary loops)");
  }
  std::map<int, size_t> seen;  // vertex -> first landmark on it
  for (size_t i = 0; i < landmarks.size(); ++i) {
    if (const std::string why = invalid_point(mesh, landmarks[i]); !why.empty()) {
      throw InvalidInputError(std::string("cut: landmark ") + std::to_string(i) + " of mesh " + name + " is " + why);
    }
    const SurfacePoint p = landmarks[i].kind == SurfacePoint::Kind::kFace
                               ? canonical_point(mesh, landmarks[i].face, landmarks[i].bary)
                               : landmarks[i];
    if (p.kind != SurfacePoint::Kind::kVertex) continue;  // points apart from vertices: insert_landmarks
    const int v = p.vertex.idx;
    const auto [it, fresh] = seen.emplace(v, i);
    if (!fresh) {
      throw InvalidInputError(std::string("cut: landmarks ") + std::to_string(it->second) + " and " +
                              std::to_string(i) + " of mesh " + name + " are on the same vertex " + std::to_string(v) +
                              " (each landmark needs its own vertex)");
    }
  }
  const auto dist = edge_graph_distances(mesh, V, some_vertex(mesh, landmarks[0]));
  for (size_t v = 0; v < dist.size(); ++v) {
    if (!mesh.is_isolated(VertexId(static_cast<int>(v))) && !std::isfinite(dist[v])) {
      throw InvalidInputError(std::string("cut: mesh ") + name + " is not connected (vertex " + std::to_string(v) +
                              " cannot be reached from landmark 0)");
    }
  }
}

std::vector<VertexId> as_vertices(const std::vector<int>& ids) {
  std::vector<VertexId> v;
  v.reserve(ids.size());
  for (const int id : ids) v.emplace_back(id);
  return v;
}

/// Each landmark's refined vertex read off the ends of the paths (from child to parent landmark of each edge).
void renumber_landmarks(const std::vector<std::array<int, 2>>& edges, const std::vector<std::vector<int>>& paths,
                        std::vector<int>& landmarks) {
  for (size_t e = 0; e < edges.size(); ++e) {
    landmarks[static_cast<size_t>(edges[e][1])] = paths[e].front();
    landmarks[static_cast<size_t>(edges[e][0])] = paths[e].back();
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

std::vector<SurfacePoint> vertex_points(const std::vector<VertexId>& vertices) {
  std::vector<SurfacePoint> points;
  points.reserve(vertices.size());
  for (const VertexId v : vertices) points.push_back(SurfacePoint::at_vertex(v));
  return points;
}

CutResult cut_meshes(const Eigen::MatrixXd& VA, const Eigen::MatrixXi& FA, const Eigen::MatrixXd& VB,
                     const Eigen::MatrixXi& FB, const std::vector<VertexId>& landmarks_a,
                     const std::vector<VertexId>& landmarks_b, const CutOptions& options) {
  return cut_meshes(VA, FA, VB, FB, vertex_points(landmarks_a), vertex_points(landmarks_b), options);
}

CutResult cut_meshes(const Eigen::MatrixXd& VA, const Eigen::MatrixXi& FA, const Eigen::MatrixXd& VB,
                     const Eigen::MatrixXi& FB, const std::vector<SurfacePoint>& landmarks_a,
                     const std::vector<SurfacePoint>& landmarks_b, const CutOptions& options) {
  if (landmarks_a.size() != landmarks_b.size()) {
    throw InvalidInputError("cut: " + std::to_string(landmarks_a.size()) + " landmarks on mesh A but " +
                            std::to_string(landmarks_b.size()) + " on mesh B");
  }
  if (landmarks_a.size() < 2) throw InvalidInputError("cut: at least 2 landmark pairs are needed");
  const Mesh mesh_a(FA, static_cast<int>(VA.rows()));
  const Mesh mesh_b(FB, static_cast<int>(VB.rows()));
  check_input(mesh_a, VA, landmarks_a, "A");
  check_input(mesh_b, VB, landmarks_b, "B");

  RefinedMesh ra = make_refined_mesh(mesh_a, VA);
  RefinedMesh rb = make_refined_mesh(mesh_b, VB);
  std::vector<int> la = insert_landmarks(ra, mesh_a, landmarks_a);
  std::vector<int> lb = insert_landmarks(rb, mesh_b, landmarks_b);
  const Eigen::MatrixXd W = landmark_distances(ra.mesh, ra.vertex_matrix(), as_vertices(la)) +
                            landmark_distances(rb.mesh, rb.vertex_matrix(), as_vertices(lb));
  CutResult result;
  result.tree = options.tree == CutOptions::Tree::kPath ? path_tree(W) : minimum_spanning_tree(W);

  TraceOptions trace;
  trace.steiner = options.geodesic_paths;
  trace.shorten = options.geodesic_paths;
  TracedPaths traced = trace_cut_paths(ra, mesh_a, la, rb, mesh_b, lb, result.tree, trace);
  // The paths straight across input faces and the vertices of intermediate paths gone before the two sides'
  // vertices are paired, then the faces that the paired vertices split re-triangulated once more.
  // Each side's steps are independent of the other's: one thread each where two are available.
  const std::array<RefinedMesh*, 2> refined{&ra, &rb};
  const std::array<const Mesh*, 2> input{&mesh_a, &mesh_b};
  const std::array<std::vector<std::vector<int>>*, 2> paths{&traced.paths_a, &traced.paths_b};
  const auto remesh = [&](bool straighten) {
    parallel_for_each(2, 2, [&](int s) { remesh_along_paths(*refined[s], *input[s], *paths[s], straighten); });
  };
  if (options.remesh) remesh(true);
  equalize_paths(ra, mesh_a, traced.paths_a, rb, mesh_b, traced.paths_b, options.snap);
  if (options.remesh) remesh(false);
  // Re-triangulation renumbers the vertices after the input's; the landmarks are the paths' ends.
  renumber_landmarks(traced.edges, traced.paths_a, la);
  renumber_landmarks(traced.edges, traced.paths_b, lb);

  const std::array<const std::vector<int>*, 2> landmarks{&la, &lb};
  const std::array<CutSide*, 2> side{&result.a, &result.b};
  std::array<CutDisk, 2> disk;
  parallel_for_each(
      2, 2, [&](int s) { *side[s] = finish(*refined[s], *input[s], *landmarks[s], std::move(*paths[s]), disk[s]); });
  const Mesh cut_a(disk[0].F, static_cast<int>(disk[0].to_refined.size()));
  const Mesh cut_b(disk[1].F, static_cast<int>(disk[1].to_refined.size()));
  result.nu = match_boundaries({&cut_a, &disk[0].to_refined, &la, &result.a.paths},
                               {&cut_b, &disk[1].to_refined, &lb, &result.b.paths});
  return result;
}

}  // namespace liftmap
