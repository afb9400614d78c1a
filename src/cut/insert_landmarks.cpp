#include "cut/insert_landmarks.h"

#include <string>

#include "core/errors.h"
#include "cut/remesh_along_paths.h"

namespace liftmap {

std::vector<int> insert_landmarks(RefinedMesh& refined, const Mesh& input, const std::vector<SurfacePoint>& landmarks) {
  std::vector<int> ids(landmarks.size(), -1);
  // Each new vertex as a path of one vertex: remesh_along_paths keeps it and triangulates its input face around it.
  std::vector<std::vector<int>> single;
  std::vector<size_t> of_single;
  for (size_t i = 0; i < landmarks.size(); ++i) {
    SurfacePoint p = landmarks[i];
    if (p.kind == SurfacePoint::Kind::kFace) p = canonical_point(input, p.face, p.bary);
    if (p.kind == SurfacePoint::Kind::kVertex) {
      ids[i] = p.vertex.idx;
      continue;
    }
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    const SurfacePoint f = as_face_point(input, p);
    const auto corners = input.face_vertices(f.face);
    for (size_t k = 0; k < 3; ++k) x += f.bary[k] * refined.positions[static_cast<size_t>(corners[k].idx)];
    single.push_back({refined.n_vertices()});
    of_single.push_back(i);
    refined.positions.push_back(x);
    refined.on_input.push_back(p);
  }
  if (single.empty()) return ids;
  const RemeshStats stats = remesh_along_paths(refined, input, single);
  if (stats.kept_as_traced) {
    throw InvalidInputError(
        "cut: a landmark inside a face or on an edge is too close to another landmark or to a mesh vertex to be a "
        "vertex of its own");
  }
  for (size_t j = 0; j < single.size(); ++j) ids[of_single[j]] = single[j][0];
  return ids;
}

}  // namespace liftmap
