// Refines a closed triangle mesh to about a given number of faces for the scaling series of bench/run.py (not a
// test). Uses CGAL's Loop (x4 faces) and sqrt(3) (x3 faces) subdivision, choosing the shortest sequence of the two
// whose face count is closest to the target in ratio. Both methods append the new vertices after the old ones, so
// vertex i of the input is vertex i of the output and a landmark file keeps its meaning.
// Usage: subdivide_mesh IN.off OUT.off TARGET_FACES   (prints the face count and the steps taken)

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/subdivision_method_3.h>

#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;

// The sequence of factors 4 (Loop) and 3 (sqrt(3)), at most six steps, bringing `faces` closest to `target` in
// log ratio; on ties the shorter sequence wins.
std::vector<int> choose_steps(double faces, double target) {
  std::vector<int> best;
  double best_error = std::abs(std::log(faces / target));
  for (int loops = 0; loops <= 6; ++loops) {
    for (int sqrt3s = 0; loops + sqrt3s <= 6; ++sqrt3s) {
      const double error = std::abs(std::log(faces * std::pow(4.0, loops) * std::pow(3.0, sqrt3s) / target));
      if (error < best_error - 1e-12 ||
          (std::abs(error - best_error) <= 1e-12 && loops + sqrt3s < static_cast<int>(best.size()))) {
        best_error = error;
        best.assign(static_cast<size_t>(loops), 4);
        best.insert(best.end(), static_cast<size_t>(sqrt3s), 3);
      }
    }
  }
  return best;
}

// Reads argv[1], refines it towards argv[3] faces, writes argv[2]; returns the exit code.
int run(char** argv) {
  SurfaceMesh mesh;
  // read_OFF keeps the file's vertex order (read_polygon_mesh may repair and re-index the soup).
  std::ifstream in(argv[1]);
  if (!in || !CGAL::IO::read_OFF(in, mesh) || !CGAL::is_triangle_mesh(mesh) || !CGAL::is_closed(mesh)) {
    std::fprintf(stderr, "subdivide_mesh: %s: cannot read a closed triangle mesh\n", argv[1]);
    return 3;
  }
  const std::vector<int> steps = choose_steps(static_cast<double>(mesh.number_of_faces()), std::stod(argv[3]));
  std::string names;
  for (const int factor : steps) {
    if (factor == 4) {
      CGAL::Subdivision_method_3::Loop_subdivision(mesh);
    } else {
      CGAL::Subdivision_method_3::Sqrt3_subdivision(mesh);
    }
    names += factor == 4 ? " loop" : " sqrt3";
  }
  std::ofstream out(argv[2]);
  if (!out || !CGAL::IO::write_OFF(out, mesh, CGAL::parameters::stream_precision(17))) {
    std::fprintf(stderr, "subdivide_mesh: cannot write %s\n", argv[2]);
    return 3;
  }
  std::printf("%zu faces%s\n", static_cast<size_t>(mesh.number_of_faces()),
              names.empty() ? " (unchanged)" : names.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s IN.off OUT.off TARGET_FACES\n", argv[0]);
    return 2;
  }
  try {
    return run(argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "subdivide_mesh: %s\n", e.what());
    return 1;
  }
}
