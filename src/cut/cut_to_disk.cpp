#include "cut/cut_to_disk.h"

#include <algorithm>

namespace liftmap {

CutDisk cut_to_disk(const Mesh& mesh, const std::vector<char>& is_cut) {
  const auto cut = [&](HalfedgeId h) { return is_cut[static_cast<size_t>(Mesh::edge(h).idx)] != 0; };
  // Copy of vertex v used by face corner (f, k), k in face_vertices order.
  std::vector<int> corner(static_cast<size_t>(3 * mesh.n_faces()), -1);
  std::vector<int> to_refined;
  std::vector<HalfedgeId> fan;
  for (int v = 0; v < mesh.n_vertices(); ++v) {
    if (mesh.is_isolated(VertexId(v))) continue;
    fan.clear();
    mesh.for_each_outgoing(VertexId(v), [&](HalfedgeId h) { fan.push_back(h); });
    // Start the walk at a cut edge, so that each wedge between consecutive cut edges is one copy.
    const auto first = std::find_if(fan.begin(), fan.end(), cut);
    if (first != fan.end()) std::rotate(fan.begin(), first, fan.end());
    int copy = -1;
    for (size_t i = 0; i < fan.size(); ++i) {
      const HalfedgeId h = fan[i];
      if (copy < 0 || cut(h)) {
        copy = static_cast<int>(to_refined.size());
        to_refined.push_back(v);
      }
      if (mesh.is_boundary(h)) continue;
      const FaceId f = mesh.face(h);
      const auto fh = mesh.face_halfedges(f);
      for (int k = 0; k < 3; ++k) {
        if (fh[static_cast<size_t>(k)] == h) corner[static_cast<size_t>(3 * f.idx + k)] = copy;
      }
    }
  }
  CutDisk out;
  out.F.resize(mesh.n_faces(), 3);
  for (int f = 0; f < mesh.n_faces(); ++f) {
    for (int k = 0; k < 3; ++k) out.F(f, k) = corner[static_cast<size_t>(3 * f + k)];
  }
  out.to_refined = Eigen::Map<const Eigen::VectorXi>(to_refined.data(), static_cast<int>(to_refined.size()));
  return out;
}

}  // namespace liftmap
