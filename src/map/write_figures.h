#pragma once
/// The pictures and textured meshes of `liftmap map` (README, "Output files").

#include <string>

#include "io/read_mesh.h"
#include "map/map_meshes.h"

namespace liftmap {

/// Writes `render.png`: A painted with a 3D checker texture, B painted by pulling that texture back through the
/// map at every pixel (seamless across the cut), landmarks as dots in matching colours, cut graphs in green,
/// matching viewpoints (the paper's Figure 1).
/// \param label_a, label_b captions of the two panels
void write_map_render(const std::string& path, const MapResult& map, const TriangleMesh& a, const TriangleMesh& b,
                      const std::vector<SurfacePoint>& landmarks_a, const std::vector<SurfacePoint>& landmarks_b,
                      const std::string& label_a, const std::string& label_b);

/// Writes `distortion.png`: the area-weighted histogram of the sampled distortion of f with its mean (Figure 9).
void write_distortion_histogram(const std::string& path, const MapResult& map);

/// Writes `A_textured.obj/.mtl`, `B_textured.obj/.mtl` and `texture.png` into `folder`: A with texture
/// coordinates from its flattening Phi, B with Psi = Phi o g in the same texture space, so B shows A's texture
/// carried over by the map. Both open in MeshLab or Blender.
void write_textured_meshes(const std::string& folder, const MapResult& map);

}  // namespace liftmap
