#include "render/figure.h"

#include <algorithm>
#include <string>

#include "core/errors.h"
#include "render/colour_maps.h"
#include "render/rasterize.h"
#include "render/text.h"

namespace liftmap {
namespace {

SimilarityTransform align_panels(const FigurePanel& a, const FigurePanel& b) {
  if (a.landmarks.rows() >= 2) {
    // The vertex centroids as one more corresponding pair: they settle the rotation about the line through two
    // landmarks and barely move a fit to many.
    Eigen::MatrixXd P(a.landmarks.rows() + 1, 3), Q(b.landmarks.rows() + 1, 3);
    P << a.landmarks, a.V.colwise().mean();
    Q << b.landmarks, b.V.colwise().mean();
    return align_similarity(P, Q);
  }
  const Sphere sa = bounding_sphere(a.V), sb = bounding_sphere(b.V);
  SimilarityTransform s;
  s.scale = sa.radius / std::max(sb.radius, 1e-300);
  s.t = sa.center - s.scale * sb.center;
  return s;
}

Image render_panel(const FigurePanel& panel, const Eigen::MatrixXd& V, std::vector<Eigen::MatrixXd> cut_paths,
                   const Eigen::MatrixXd& landmarks, const CheckerTexture& texture, const ViewDirection& view,
                   const MapFigureOptions& options, int width) {
  RasterOptions raster;
  raster.width = width;
  raster.height = options.height;
  raster.supersampling = options.supersampling;
  raster.background = options.background;
  raster.specular = 0.12;
  SurfaceOverlays overlays;
  overlays.polylines = std::move(cut_paths);
  const double size = options.height / 800.0;
  overlays.polyline_width = options.cut_width * size;
  overlays.points = landmarks;
  overlays.point_colours = landmark_colours(static_cast<int>(landmarks.rows()));
  overlays.point_radius = options.point_radius * size;
  overlays.outline_width *= size;
  // Leave room at the bottom for the label.
  const double fill = 0.86;
  const Camera camera =
      fit_camera(V, view.direction, view.up, static_cast<double>(width) / options.height, options.projection, fill);
  if (panel.T.rows() > 0) return rasterize(V, panel.F, panel.T, texture, camera, overlays, raster);
  if (panel.C.rows() > 0) return rasterize(V, panel.F, panel.C, camera, overlays, raster);
  return rasterize(V, panel.F, panel.V, texture, camera, overlays, raster);
}

}  // namespace

Image render_map_figure(const FigurePanel& a, const FigurePanel& b, const MapFigureOptions& options) {
  if (options.width < 2 || options.height < 1) throw InvalidInputError("render_map_figure: non-positive size");
  if (a.landmarks.rows() != b.landmarks.rows())
    throw InvalidInputError("render_map_figure: the panels have different numbers of landmarks");
  if (b.T.rows() == 0 && b.C.rows() == 0)
    throw InvalidInputError("render_map_figure: panel B needs texture coordinates T or colours C");
  for (const FigurePanel* p : {&a, &b})
    for (const Eigen::MatrixXd* M : {&p->T, &p->C})
      if (M->rows() > 0 && (M->rows() != p->V.rows() || M->cols() != 3))
        throw InvalidInputError("render_map_figure: T and C must be #V by 3 (" + std::to_string(p->V.rows()) +
                                " by 3), got " + std::to_string(M->rows()) + " by " + std::to_string(M->cols()));
  const CheckerTexture texture = make_checker_texture(a.V, options.checker_cells);
  const SimilarityTransform to_a = align_panels(a, b);
  std::vector<Eigen::MatrixXd> cuts_b;
  for (const Eigen::MatrixXd& P : b.cut_paths) cuts_b.push_back(to_a.apply(P));
  const Eigen::MatrixXd Vb = to_a.apply(b.V);
  const Eigen::MatrixXd Lb = b.landmarks.rows() > 0 ? to_a.apply(b.landmarks) : b.landmarks;
  const ViewDirection view = options.view ? *options.view : default_view(a.V, a.landmarks);

  const int half = options.width / 2;
  Image figure(options.width, options.height, options.background);
  paste(figure, render_panel(a, a.V, a.cut_paths, a.landmarks, texture, view, options, half), 0, 0);
  paste(figure, render_panel(b, Vb, cuts_b, Lb, texture, view, options, options.width - half), half, 0);

  const int scale = options.height >= 600 ? 3 : 2;
  const Eigen::Vector3d ink(0.2, 0.2, 0.2);
  const int y = options.height - (kTextHeight + 4) * scale;
  draw_text(figure, (half - text_width(a.label, scale)) / 2, y, a.label, ink, scale);
  draw_text(figure, half + (options.width - half - text_width(b.label, scale)) / 2, y, b.label, ink, scale);
  return figure;
}

}  // namespace liftmap
