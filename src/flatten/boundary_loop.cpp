#include "flatten/boundary_loop.h"

#include <algorithm>
#include <string>

#include "core/errors.h"

namespace liftmap {

std::vector<VertexId> ccw_boundary_loop(const Mesh& mesh) {
  const auto loops = mesh.boundary_loops();
  if (loops.size() != 1 || mesh.euler_characteristic() != 1) {
    throw InvalidInputError("flatten: the mesh is not a disk (" + std::to_string(loops.size()) +
                            " boundary loops, Euler characteristic " + std::to_string(mesh.euler_characteristic()) +
                            ")");
  }
  // Boundary halfedges run clockwise around the interior (their left side is outside): reversing their heads
  // gives t0, t_{n-1}, ..., t1 for tails t_i.
  std::vector<VertexId> loop;
  loop.reserve(loops[0].size());
  for (const HalfedgeId h : loops[0]) loop.push_back(mesh.head(h));
  std::reverse(loop.begin(), loop.end());
  return loop;
}

}  // namespace liftmap
