#pragma once
/// The overlay of a map (README, "Output folder": overlay.obj): the common refinement of the input meshes A and B.

#include "core/overlay.h"
#include "map/map_meshes.h"

namespace liftmap {

/// The common refinement of A and B under `map`: the overlay of the two disks (overlay_disks), with the copies of
/// each cut-path point on the two sides of the cut made one vertex again, and every vertex expressed on the input
/// meshes. The result is a closed genus-0 mesh; every triangle lies in one face of A and one face of B, on which
/// the map is affine.
/// \param agreement if not null, receives the largest distance in R^3 between an overlay vertex's point on one
///        disk and the bijection's image (f or g) of its point on the other, over all vertices and both directions,
///        relative to the square root of the area of the disk it is measured on
/// \pre `map` is a result of map_meshes (it has its cut, flattening and bijection)
/// \throw PipelineError if the flattenings do not cover each other (not a liftable pair; map_meshes rejects those)
Overlay overlay_of_map(const MapResult& map, double* agreement = nullptr);

}  // namespace liftmap
