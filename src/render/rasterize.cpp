#include "render/rasterize.h"

#include <omp.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/errors.h"

namespace liftmap {
namespace {

constexpr float kFar = std::numeric_limits<float>::infinity();

/// The supersampled frame: sample buffers and the projection of the mesh's vertices into sample coordinates.
struct Frame {
  int w = 0, h = 0;  // samples
  int s = 1;         // supersampling factor
  Camera camera;
  double aspect = 1;
  std::vector<float> depth;  // w*h, kFar where empty
  std::vector<int> face;     // w*h, -1 where empty or covered by an overlay only
  Image colour;              // w by h samples

  Eigen::Vector2d to_sample(const Eigen::Vector2d& ndc) const {
    return {0.5 * (ndc.x() + 1.0) * w, 0.5 * (1.0 - ndc.y()) * h};
  }
  std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * w + x; }
  bool perspective() const { return camera.projection == Projection::kPerspective; }
  /// Depth at parameter t along a screen-space segment between depths z0 and z1 (1/z is screen-linear under
  /// perspective).
  double depth_along(double z0, double z1, double t) const {
    return perspective() ? 1.0 / ((1.0 - t) / z0 + t / z1) : (1.0 - t) * z0 + t * z1;
  }
};

Eigen::Vector3d row3(const Eigen::MatrixXd& M, Eigen::Index i) { return M.row(i).transpose(); }

double edge(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  return (b.x() - a.x()) * (p.y() - a.y()) - (b.y() - a.y()) * (p.x() - a.x());
}

void check_inputs(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& A, const char* what,
                  const RasterOptions& options) {
  if (V.cols() != 3 || V.rows() == 0) throw InvalidInputError("rasterize: V must be a non-empty #V by 3 matrix");
  if (F.cols() != 3) throw InvalidInputError("rasterize: F must be #F by 3");
  if (A.rows() != V.rows() || A.cols() != 3)
    throw InvalidInputError(std::string("rasterize: ") + what + " must be #V by 3 (" + std::to_string(V.rows()) +
                            " by 3), got " + std::to_string(A.rows()) + " by " + std::to_string(A.cols()));
  if (F.size() > 0 && (F.minCoeff() < 0 || F.maxCoeff() >= V.rows()))
    throw InvalidInputError("rasterize: face index out of range");
  if (options.width <= 0 || options.height <= 0 || options.supersampling <= 0)
    throw InvalidInputError("rasterize: image size and supersampling must be positive");
}

Eigen::MatrixXd vertex_normals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(V.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d n = (row3(V, F(f, 1)) - row3(V, F(f, 0))).cross(row3(V, F(f, 2)) - row3(V, F(f, 0)));
    for (int k = 0; k < 3; ++k) N.row(F(f, k)) += n.transpose();  // area-weighted
  }
  for (Eigen::Index i = 0; i < N.rows(); ++i) {
    const double len = N.row(i).norm();
    if (len > 0) N.row(i) /= len;
  }
  return N;
}

/// The depth test of rows y_first to y_last: each sample keeps the nearest face covering it (the first of equal
/// depths), faces in order. xy, z: the vertices' sample positions and depths; faces with a vertex nearer than `near`
/// are skipped.
void depth_test_rows(Frame& frame, const Eigen::MatrixXi& F, const std::vector<Eigen::Vector2d>& xy,
                     const std::vector<double>& z, double near, int y_first, int y_last) {
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const int a = F(f, 0), b = F(f, 1), c = F(f, 2);
    if (z[a] <= near || z[b] <= near || z[c] <= near) continue;
    const double ymin = std::min({xy[a].y(), xy[b].y(), xy[c].y()});
    const double ymax = std::max({xy[a].y(), xy[b].y(), xy[c].y()});
    const int y0 = std::max(y_first, static_cast<int>(std::ceil(ymin - 0.5)));
    const int y1 = std::min(y_last, static_cast<int>(std::floor(ymax - 0.5)));
    if (y0 > y1) continue;
    const double area = edge(xy[a], xy[b], xy[c]);
    if (area == 0.0 || !std::isfinite(area)) continue;
    const double xmin = std::min({xy[a].x(), xy[b].x(), xy[c].x()});
    const double xmax = std::max({xy[a].x(), xy[b].x(), xy[c].x()});
    const int x0 = std::max(0, static_cast<int>(std::ceil(xmin - 0.5)));
    const int x1 = std::min(frame.w - 1, static_cast<int>(std::floor(xmax - 0.5)));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const Eigen::Vector2d p(x + 0.5, y + 0.5);
        const double w0 = edge(xy[b], xy[c], p) / area;
        const double w1 = edge(xy[c], xy[a], p) / area;
        const double w2 = edge(xy[a], xy[b], p) / area;
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        const double d =
            frame.perspective() ? 1.0 / (w0 / z[a] + w1 / z[b] + w2 / z[c]) : w0 * z[a] + w1 * z[b] + w2 * z[c];
        const std::size_t k = frame.index(x, y);
        if (d < frame.depth[k]) {
          frame.depth[k] = static_cast<float>(d);
          frame.face[k] = static_cast<int>(f);
        }
      }
  }
}

/// Renders the mesh into the frame: visibility by z-buffer, then one shading evaluation per covered sample.
/// `albedo(f, w)` is the surface colour at perspective-correct barycentric weights w of face f.
template <class Albedo>
void draw_mesh(Frame& frame, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const RasterOptions& options,
               const Albedo& albedo) {
  std::vector<Eigen::Vector2d> xy(V.rows());
  std::vector<double> z(V.rows());
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const ProjectedPoint q = project(frame.camera, frame.aspect, row3(V, i));
    xy[i] = frame.to_sample(q.ndc);
    z[i] = q.depth;
  }
  const double near = 1e-9 * bounding_sphere(V).radius;

  // The depth test in bands of rows, one thread each: every band sees the faces in order, so a sample keeps the
  // same face whatever the threads.
  const int bands = std::min(frame.h, 4 * omp_get_max_threads());
#pragma omp parallel for schedule(dynamic, 1)
  for (int band = 0; band < bands; ++band) {
    depth_test_rows(frame, F, xy, z, near, static_cast<int>(static_cast<long>(frame.h) * band / bands),
                    static_cast<int>(static_cast<long>(frame.h) * (band + 1) / bands) - 1);
  }

  const Eigen::MatrixXd N = options.smooth_shading ? vertex_normals(V, F) : Eigen::MatrixXd();
#pragma omp parallel for schedule(dynamic, 8)
  for (int y = 0; y < frame.h; ++y)
    for (int x = 0; x < frame.w; ++x) {
      const int f = frame.face[frame.index(x, y)];
      if (f < 0) continue;
      const int a = F(f, 0), b = F(f, 1), c = F(f, 2);
      const Eigen::Vector2d p(x + 0.5, y + 0.5);
      const double area = edge(xy[a], xy[b], xy[c]);
      Eigen::Vector3d w(edge(xy[b], xy[c], p) / area, edge(xy[c], xy[a], p) / area, edge(xy[a], xy[b], p) / area);
      if (frame.perspective()) w = Eigen::Vector3d(w[0] / z[a], w[1] / z[b], w[2] / z[c]);
      w /= w.sum();
      const Eigen::Vector3d pos = (w[0] * V.row(a) + w[1] * V.row(b) + w[2] * V.row(c)).transpose();
      Eigen::Vector3d n = options.smooth_shading
                              ? Eigen::Vector3d((w[0] * N.row(a) + w[1] * N.row(b) + w[2] * N.row(c)).transpose())
                              : Eigen::Vector3d((row3(V, b) - row3(V, a)).cross(row3(V, c) - row3(V, a)));
      const Eigen::Vector3d light = frame.perspective() ? Eigen::Vector3d(frame.camera.eye - pos)
                                                        : Eigen::Vector3d(frame.camera.eye - frame.camera.target);
      const double nl = n.norm() > 0 ? std::abs(n.normalized().dot(light.normalized())) : 1.0;
      frame.colour.set(x, y,
                       albedo(f, w) * (options.ambient + options.diffuse * nl) +
                           Eigen::Vector3d::Constant(
                               options.specular > 0 ? options.specular * std::pow(nl, options.shininess) : 0.0));
    }

  if (options.silhouette_width <= 0) return;
  // Contours: a sample is on one when a sample within the contour width is empty or much farther away.
  const int r = std::max(1, static_cast<int>(std::lround(options.silhouette_width * frame.s)));
  const float jump = static_cast<float>(0.04 * bounding_sphere(V).radius);
  std::vector<char> contour(frame.depth.size(), 0);
#pragma omp parallel for schedule(dynamic, 8)
  for (int y = 0; y < frame.h; ++y)
    for (int x = 0; x < frame.w; ++x) {
      const float d = frame.depth[frame.index(x, y)];
      if (d == kFar) continue;
      bool on = false;
      for (int dy = -r; dy <= r && !on; ++dy)
        for (int dx = -r; dx <= r && !on; ++dx) {
          if (dx * dx + dy * dy > r * r) continue;
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= frame.w || yy >= frame.h) continue;
          on = frame.depth[frame.index(xx, yy)] > d + jump;
        }
      contour[frame.index(x, y)] = on;
    }
  const Eigen::Vector3d ink(0.15, 0.15, 0.15);
  for (int y = 0; y < frame.h; ++y)
    for (int x = 0; x < frame.w; ++x)
      if (contour[frame.index(x, y)]) frame.colour.blend(x, y, ink, 0.8);
}

void draw_polylines(Frame& frame, const SurfaceOverlays& overlays, double bias) {
  if (overlays.polylines.empty()) return;
  const double hw = 0.5 * overlays.polyline_width * frame.s;
  // Every sample keeps its distance to the nearest visible centreline, so that segments join without seams;
  // the samples are painted once all segments are in.
  std::vector<float> distance(frame.depth.size(), kFar), line_depth(frame.depth.size(), kFar);
  for (const Eigen::MatrixXd& P : overlays.polylines) {
    if (P.cols() != 3) throw InvalidInputError("rasterize: polylines must be #P by 3");
    for (Eigen::Index i = 0; i + 1 < P.rows(); ++i) {
      const ProjectedPoint qa = project(frame.camera, frame.aspect, row3(P, i));
      const ProjectedPoint qb = project(frame.camera, frame.aspect, row3(P, i + 1));
      if (qa.depth <= 0 || qb.depth <= 0) continue;
      const Eigen::Vector2d a = frame.to_sample(qa.ndc), b = frame.to_sample(qb.ndc);
      const Eigen::Vector2d ab = b - a;
      const double len2 = ab.squaredNorm();
      const int x0 = std::max(0, static_cast<int>(std::floor(std::min(a.x(), b.x()) - hw)));
      const int x1 = std::min(frame.w - 1, static_cast<int>(std::ceil(std::max(a.x(), b.x()) + hw)));
      const int y0 = std::max(0, static_cast<int>(std::floor(std::min(a.y(), b.y()) - hw)));
      const int y1 = std::min(frame.h - 1, static_cast<int>(std::ceil(std::max(a.y(), b.y()) + hw)));
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const Eigen::Vector2d p(x + 0.5, y + 0.5);
          const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
          const double dist = (p - (a + t * ab)).norm();
          const std::size_t k = frame.index(x, y);
          if (dist > hw || dist >= distance[k]) continue;
          const double d = frame.depth_along(qa.depth, qb.depth, t) - bias;
          if (d >= frame.depth[k]) continue;
          distance[k] = static_cast<float>(dist);
          line_depth[k] = static_cast<float>(d);
        }
    }
  }
  for (int y = 0; y < frame.h; ++y)
    for (int x = 0; x < frame.w; ++x) {
      const std::size_t k = frame.index(x, y);
      if (distance[k] == kFar) continue;
      frame.depth[k] = line_depth[k];
      // Shaded across its width like a tube, so that the path reads as lying on the surface.
      const double u = distance[k] / hw;
      frame.colour.set(x, y, overlays.polyline_colour * (0.6 + 0.4 * std::sqrt(std::max(0.0, 1.0 - u * u))));
    }
}

void draw_points(Frame& frame, const SurfaceOverlays& overlays, const RasterOptions& options, double bias) {
  const Eigen::MatrixXd& P = overlays.points;
  if (P.rows() == 0) return;
  if (P.cols() != 3) throw InvalidInputError("rasterize: points must be #L by 3");
  const bool coloured = overlays.point_colours.rows() > 0;
  if (coloured && (overlays.point_colours.rows() != P.rows() || overlays.point_colours.cols() != 3))
    throw InvalidInputError("rasterize: point_colours must be #L by 3, one row per point");
  const double r = overlays.point_radius * frame.s;
  const double ring = overlays.outline_width * frame.s;
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const ProjectedPoint q = project(frame.camera, frame.aspect, row3(P, i));
    if (q.depth <= 0) continue;
    const Eigen::Vector2d c = frame.to_sample(q.ndc);
    // The dot is a sphere of r samples: its world radius at the depth of its centre.
    const double world_r = r * 2.0 * half_height_at_depth(frame.camera, q.depth) / frame.h;
    const Eigen::Vector3d albedo =
        coloured ? Eigen::Vector3d(overlays.point_colours.row(i).transpose()) : Eigen::Vector3d(0.9, 0.1, 0.1);
    const int x0 = std::max(0, static_cast<int>(std::floor(c.x() - r)));
    const int x1 = std::min(frame.w - 1, static_cast<int>(std::ceil(c.x() + r)));
    const int y0 = std::max(0, static_cast<int>(std::floor(c.y() - r)));
    const int y1 = std::min(frame.h - 1, static_cast<int>(std::ceil(c.y() + r)));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double dist = (Eigen::Vector2d(x + 0.5, y + 0.5) - c).norm();
        if (dist > r) continue;
        const double nz = std::sqrt(std::max(0.0, 1.0 - (dist / r) * (dist / r)));
        // The sphere is tested as if it sat on the surface rather than half inside it: a landmark stays visible
        // where its surface point is, even on thin features (hooves, fingertips).
        const double d = q.depth - (1.0 + nz) * world_r - bias;
        const std::size_t k = frame.index(x, y);
        if (d >= frame.depth[k]) continue;
        frame.depth[k] = static_cast<float>(d);
        frame.colour.set(x, y,
                         dist > r - ring ? overlays.outline_colour
                                         : Eigen::Vector3d(albedo * (options.ambient + options.diffuse * nz)));
      }
  }
}

template <class Albedo>
Image render(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Camera& camera, const SurfaceOverlays& overlays,
             const RasterOptions& options, const Albedo& albedo) {
  Frame frame;
  frame.s = options.supersampling;
  frame.w = options.width * frame.s;
  frame.h = options.height * frame.s;
  frame.camera = camera;
  frame.aspect = static_cast<double>(options.width) / options.height;
  frame.depth.assign(static_cast<std::size_t>(frame.w) * frame.h, kFar);
  frame.face.assign(frame.depth.size(), -1);
  frame.colour = Image(frame.w, frame.h, options.background);
  draw_mesh(frame, V, F, options, albedo);
  const double bias = options.overlay_bias * bounding_sphere(V).radius;
  draw_polylines(frame, overlays, bias);
  draw_points(frame, overlays, options, bias);
  return downsample(frame.colour, frame.s);
}

}  // namespace

Image rasterize(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& C, const Camera& camera,
                const SurfaceOverlays& overlays, const RasterOptions& options) {
  check_inputs(V, F, C, "C", options);
  return render(V, F, camera, overlays, options, [&](int f, const Eigen::Vector3d& w) {
    return Eigen::Vector3d((w[0] * C.row(F(f, 0)) + w[1] * C.row(F(f, 1)) + w[2] * C.row(F(f, 2))).transpose());
  });
}

Image rasterize(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& T,
                const SolidTexture& texture, const Camera& camera, const SurfaceOverlays& overlays,
                const RasterOptions& options) {
  check_inputs(V, F, T, "T", options);
  if (!texture) throw InvalidInputError("rasterize: no texture function given");
  return render(V, F, camera, overlays, options, [&](int f, const Eigen::Vector3d& w) {
    return texture((w[0] * T.row(F(f, 0)) + w[1] * T.row(F(f, 1)) + w[2] * T.row(F(f, 2))).transpose());
  });
}

}  // namespace liftmap
