#pragma once
// Access to test meshes: the libcgal-demo meshes (scripts/get-meshes.sh) and the small files of tests/data.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <string>

#include "core/surface_point.h"
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

/// Position in R^3 of a face point `p` of mesh `m`.
inline Eigen::Vector3d position(const TriangleMesh& m, const SurfacePoint& p) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) x += p.bary[static_cast<size_t>(k)] * m.V.row(m.F(p.face.idx, k)).transpose();
  return x;
}

/// The square root of the surface area of `m` (the unit of map errors).
inline double sqrt_area(const TriangleMesh& m) {
  double a = 0;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector3d p = m.V.row(m.F(f, 0)), q = m.V.row(m.F(f, 1)), r = m.V.row(m.F(f, 2));
    a += 0.5 * (q - p).cross(r - p).norm();
  }
  return std::sqrt(a);
}

}  // namespace liftmap::testing
