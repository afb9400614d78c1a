#pragma once
/// What the overlay fuzz target does with its input, shared with the test that replays its seed, mutations of it
/// and the regression inputs of tests/data/fuzz-regressions/overlay/.

#include <Eigen/Core>
#include <string>

#include "map/bake_texture.h"
#include "map/overlay_files.h"
#include "map/transfer.h"
#include "read_as_fuzzed.h"

namespace liftmap::fuzz {

/// The fuzzed input as an overlay's three files: overlay.obj, overlay_points.txt and overlay_faces.txt, in this
/// order, separated by NUL bytes (a missing part is an empty file).
inline OverlayTexts overlay_texts_of(const std::string& data) {
  OverlayTexts t;
  std::string* parts[3] = {&t.obj, &t.points, &t.faces};
  size_t start = 0;
  for (int k = 0; k < 3 && start <= data.size(); ++k) {
    const size_t end = k < 2 ? data.find('\0', start) : std::string::npos;
    *parts[k] = data.substr(start, end == std::string::npos ? std::string::npos : end - start);
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return t;
}

/// The octahedron with texture coordinates from its x and y (one per vertex).
inline TexturedMesh fuzz_textured_octahedron() {
  const TriangleMesh oct = fuzz_octahedron();
  TexturedMesh m{oct.V, oct.F, {}, oct.F, {}, {}};
  m.UV = (oct.V.leftCols(2).array() + 1) / 2;
  return m;
}

/// Reads `data` (overlay_texts_of) as an overlay of the octahedron onto itself, then uses it as
/// `liftmap transfer mesh --exact` (the placed mesh and its folded faces) and `liftmap transfer texture` (a 16 by 16
/// bake of a 4 by 4 texture) do.
/// \throw IoError or InvalidInputError for bad input; anything else is a bug
inline void overlay_as_fuzzed(const std::string& data) {
  static const TexturedMesh oct = fuzz_textured_octahedron();
  const Overlay o =
      read_overlay_texts(overlay_texts_of(data), "/nonexistent-liftmap-fuzz/overlay.obj", oct.V, oct.F, oct.V, oct.F);
  const Eigen::MatrixXd placed = interpolate_at(oct.F, oct.V, o.on_b);
  (void)folded_faces(o.F, placed, oct.V, oct.F, o.on_b, o.face_b);
  static const Image texture(4, 4, Eigen::Vector3d(0.2, 0.5, 0.8));
  BakeSettings settings;
  settings.width = settings.height = 16;
  (void)bake_texture(o, oct, texture, oct, settings);
}

}  // namespace liftmap::fuzz
