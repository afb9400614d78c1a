#pragma once
/// What each fuzz target does with its input, shared with the test that replays the regression inputs of
/// tests/data/fuzz-regressions/<reader>/.

#include <sstream>
#include <string>

#include "check/check_mesh.h"
#include "io/landmarks.h"
#include "io/read_mesh.h"
#include "io/vertex_map.h"

namespace liftmap::fuzz {

/// Reads `data` with one reader and validates what it accepts, as `liftmap check` does.
/// \param reader a mesh format (".off", ".obj", ".ply", ".stl"), "landmarks" (against meshes of 1000 vertices)
///        or "vertex_map" (into a mesh of 2000 faces)
/// \throw IoError or InvalidInputError for bad input; anything else is a bug
inline void read_as_fuzzed(const std::string& reader, const std::string& data) {
  constexpr int kVertices = 1000;
  constexpr int kFaces = 2000;
  if (reader == "landmarks") {
    std::istringstream in(data);
    read_landmarks(in, "fuzz.txt", kVertices, kVertices);
  } else if (reader == "vertex_map") {
    std::istringstream in(data);
    read_vertex_map(in, "fuzz.txt", kFaces);
  } else {
    const TriangleMesh mesh = read_mesh_data(data, "fuzz" + reader);
    check_mesh(mesh.V, mesh.F);
  }
}

}  // namespace liftmap::fuzz
