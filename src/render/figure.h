#pragma once
/// render.png: the paper's Figure 1 in one picture. Mesh A painted with a solid texture, mesh B painted with that
/// texture pulled back through the map, side by side from matching viewpoints, with landmarks as dots in
/// matching colours and the cut graph in green.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "render/alignment.h"
#include "render/camera.h"
#include "render/image.h"

namespace liftmap {

/// One side of the figure: a mesh, how it is painted, and what is drawn on it.
struct FigurePanel {
  Eigen::MatrixXd V;  ///< #V by 3 vertex positions
  Eigen::MatrixXi F;  ///< #F by 3 vertex indices
  /// #V by 3 points of mesh A at which A's texture is evaluated per pixel (interpolated across faces): A's own
  /// V for panel A, the images g(y) of B's vertices on A for panel B. Empty: use C; both empty on panel A: V.
  Eigen::MatrixXd T;
  /// #V by 3 per-vertex RGB in [0,1], used when T is empty, e.g. evaluate_texture(make_checker_texture(A.V, cells),
  /// g(V_B)) for B.
  Eigen::MatrixXd C;
  std::vector<Eigen::MatrixXd> cut_paths;  ///< cut graph as polylines, each #P by 3 points on the surface
  Eigen::MatrixXd landmarks;               ///< #L by 3 landmark positions; row i matches row i of the other panel
  std::string label;                       ///< written under the panel, e.g. "A: camel.off"
};

/// Size and style of the figure.
struct MapFigureOptions {
  int width = 1600;  ///< whole figure; each panel is width/2 by height
  int height = 800;
  int supersampling = 3;
  Projection projection = Projection::kPerspective;
  int checker_cells = 14;      ///< checkerboard cubes along the longest side of A's bounding box
  double point_radius = 10.0;  ///< landmark dots, in pixels of an 800 pixel high figure (scaled with height)
  double cut_width = 4.5;      ///< cut paths, in pixels of an 800 pixel high figure (scaled with height)
  Eigen::Vector3d background{1.0, 1.0, 1.0};
  /// Viewing direction and up in A's frame; unset: default_view(A.V, A.landmarks).
  std::optional<ViewDirection> view;
};

/// Renders the two panels side by side. B (with its cut paths and landmarks) is first moved onto A by the
/// similarity transform that best aligns its landmarks and vertex centroid with A's (align_similarity;
/// bounding spheres when there are fewer than 2 landmarks), then both are drawn looking along options.view
/// (default_view of A when unset), each framed to fill its panel. Landmark i has colour landmark_colours(#L).row(i) on
/// both panels. \throw InvalidInputError for inconsistent shapes (T or C not #V by 3 where given, panel B with neither,
///        different numbers of landmarks on the two panels) or a non-positive size
Image render_map_figure(const FigurePanel& a, const FigurePanel& b, const MapFigureOptions& options = {});

}  // namespace liftmap
