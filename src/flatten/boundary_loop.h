#pragma once
/// The boundary loop of a disk, as the vertex order that the flattening stage uses everywhere.

#include <vector>

#include "core/mesh.h"

namespace liftmap {

/// The vertices of the single boundary loop of a disk, counter-clockwise (the interior on the left when walking
/// the loop), starting at the tail of the lowest-index boundary halfedge.
/// \throw InvalidInputError if the mesh is not a disk: not exactly one boundary loop, or Euler characteristic
///        other than 1.
std::vector<VertexId> ccw_boundary_loop(const Mesh& mesh);

}  // namespace liftmap
