#pragma once
/// What each fuzz target does with its input, shared with the test that replays the regression inputs of
/// tests/data/fuzz-regressions/<reader>/.

#include <sstream>
#include <string>

#include "check/check_mesh.h"
#include "io/landmarks.h"
#include "io/read_mesh.h"
#include "io/read_obj_with_uv.h"
#include "io/vertex_map.h"

namespace liftmap::fuzz {

/// The octahedron of tests/data/good/octahedron.off: the meshes surface-point landmarks are read against.
inline TriangleMesh fuzz_octahedron() {
  TriangleMesh m;
  m.V.resize(6, 3);
  m.V << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
  m.F.resize(8, 3);
  m.F << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  return m;
}

/// Reads `data` with one reader and validates what it accepts, as `liftmap check` does.
/// \param reader a mesh format (".off", ".obj", ".ply", ".stl"), "landmarks" (against meshes of 1000 vertices),
///        "surface_landmarks" (vertex, face and 3D-point tokens against the octahedron), "vertex_map" (into a mesh
///        of 2000 faces) or "obj_uv" (an OBJ with texture coordinates, as `liftmap transfer texture` reads it; its
///        `mtllib` resolved from a folder that does not exist)
/// \throw IoError or InvalidInputError for bad input; anything else is a bug
inline void read_as_fuzzed(const std::string& reader, const std::string& data) {
  constexpr int kVertices = 1000;
  constexpr int kFaces = 2000;
  if (reader == "landmarks") {
    std::istringstream in(data);
    read_landmarks(in, "fuzz.txt", kVertices, kVertices);
  } else if (reader == "surface_landmarks") {
    static const TriangleMesh oct = fuzz_octahedron();
    std::istringstream in(data);
    read_landmarks(in, "fuzz.txt", oct.V, oct.F, oct.V, oct.F);
  } else if (reader == "obj_uv") {
    const TexturedMesh mesh = read_obj_with_uv_text(data, "/nonexistent-liftmap-fuzz/fuzz.obj");
    check_mesh(mesh.V, mesh.F);
  } else if (reader == "vertex_map") {
    // The header lines are checked against a target of kFaces faces, as `transfer mesh` does.
    std::istringstream in(data);
    read_map_file(in, "fuzz.txt", {"fuzz.off", {kVertices, kFaces, 0x0123456789abcdefULL}});
  } else {
    const TriangleMesh mesh = read_mesh_data(data, "fuzz" + reader);
    check_mesh(mesh.V, mesh.F);
  }
}

}  // namespace liftmap::fuzz
