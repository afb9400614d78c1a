#pragma once
// Access to test meshes: the libcgal-demo meshes (scripts/get-meshes.sh) and the small files of tests/data.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "io/read_mesh.h"

namespace liftmap::testing {

/// Path of a libcgal-demo mesh, e.g. demo_mesh("camel.off").
inline std::string demo_mesh(const std::string& name) { return std::string(LIFTMAP_DATA_DIR) + "/" + name; }

/// Path of a file under tests/data.
inline std::string test_data(const std::string& name) { return std::string(LIFTMAP_TEST_DATA_DIR) + "/" + name; }

/// Reads a libcgal-demo mesh; fails the test with instructions if the meshes were not fetched.
inline TriangleMesh read_demo_mesh(const std::string& name) {
  const std::string path = demo_mesh(name);
  if (!std::filesystem::exists(path)) {
    ADD_FAILURE() << path << " is missing: run scripts/get-meshes.sh (make test does)";
    return {};
  }
  return read_mesh(path);
}

/// The genus-0 libcgal-demo meshes the tests run on.
inline const char* const kGenusZeroMeshes[] = {"camel.off", "cow.off",       "bull.off",        "dino.off",
                                               "man.off",   "armadillo.off", "bear.off",        "fandisk.off",
                                               "hand.off",  "homer.off",     "triceratops.off", "blobby.off"};

}  // namespace liftmap::testing
