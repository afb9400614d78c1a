#include "map/bake_texture.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "core/errors.h"

namespace liftmap {

namespace {

using Weights = std::array<double, 3>;
using Corners = std::array<Weights, 3>;

/// The overlay triangles inside each face of B (compressed rows), and every triangle's corners as barycentric
/// coordinates in its face of A and in its face of B.
struct OverlayIndex {
  std::vector<int> start;      ///< #FB + 1
  std::vector<int> triangles;  ///< #Fo, grouped by face of B
  std::vector<Corners> on_a, on_b;
};

[[noreturn]] void not_this_pair(const std::string& what) {
  throw InvalidInputError("the overlay does not belong to these meshes: " + what);
}

void check_face_range(int f, Eigen::Index n, const char* mesh, const std::string& where) {
  if (f < 0 || f >= n) {
    not_this_pair(where + " lies in face " + std::to_string(f) + " of " + mesh + ", which has " + std::to_string(n) +
                  " faces");
  }
}

/// The overlay's indices and face points are those of a mesh with A's and B's faces, at A's positions.
void check_overlay_fits(const Overlay& o, const TexturedMesh& a, const TexturedMesh& b) {
  const Eigen::Index nv = o.VA.rows();
  if (static_cast<Eigen::Index>(o.on_a.size()) != nv || static_cast<Eigen::Index>(o.on_b.size()) != nv ||
      o.face_a.size() != o.F.rows() || o.face_b.size() != o.F.rows() || (o.F.size() > 0 && o.F.maxCoeff() >= nv) ||
      (o.F.size() > 0 && o.F.minCoeff() < 0)) {
    not_this_pair("its tables and triangles have inconsistent sizes");
  }
  for (Eigen::Index t = 0; t < o.F.rows(); ++t) {
    check_face_range(o.face_a(t), a.F.rows(), "A", "triangle " + std::to_string(t));
    check_face_range(o.face_b(t), b.F.rows(), "B", "triangle " + std::to_string(t));
  }
  const double diagonal = (a.V.colwise().maxCoeff() - a.V.colwise().minCoeff()).norm();
  for (Eigen::Index i = 0; i < nv; ++i) {
    const SurfacePoint& p = o.on_a[static_cast<size_t>(i)];
    check_face_range(p.face.idx, a.F.rows(), "A", "vertex " + std::to_string(i));
    check_face_range(o.on_b[static_cast<size_t>(i)].face.idx, b.F.rows(), "B", "vertex " + std::to_string(i));
    Eigen::RowVector3d x = Eigen::RowVector3d::Zero();
    for (int k = 0; k < 3; ++k) x += p.bary[static_cast<size_t>(k)] * a.V.row(a.F(p.face.idx, k));
    if ((x - o.VA.row(i)).norm() > 1e-6 * diagonal) {
      not_this_pair("vertex " + std::to_string(i) + " is at " + figure((x - o.VA.row(i)).norm() / diagonal) +
                    " of A's bounding box diagonal from its point of A");
    }
  }
}

void check_layout(const TexturedMesh& m, const char* mesh) {
  if (m.FT.rows() != m.F.rows() || m.FT.cols() != 3 || m.UV.cols() != 2 ||
      (m.FT.size() > 0 && (m.FT.minCoeff() < 0 || m.FT.maxCoeff() >= m.UV.rows()))) {
    throw InvalidInputError(std::string("the UV layout of ") + mesh + " does not match its faces");
  }
  if (!m.UV.allFinite()) throw InvalidInputError(std::string("a texture coordinate of ") + mesh + " is not finite");
}

OverlayIndex index_overlay(const Overlay& o, const TexturedMesh& a, const TexturedMesh& b) {
  OverlayIndex index;
  const auto n = static_cast<size_t>(o.F.rows());
  index.start.assign(static_cast<size_t>(b.F.rows()) + 1, 0);
  for (size_t t = 0; t < n; ++t) ++index.start[static_cast<size_t>(o.face_b(static_cast<Eigen::Index>(t))) + 1];
  for (size_t f = 0; f + 1 < index.start.size(); ++f) index.start[f + 1] += index.start[f];
  std::vector<int> next(index.start.begin(), index.start.end() - 1);
  index.triangles.resize(n);
  index.on_a.resize(n);
  index.on_b.resize(n);
  for (size_t t = 0; t < n; ++t) {
    const int ti = static_cast<int>(t);
    index.triangles[static_cast<size_t>(next[static_cast<size_t>(o.face_b(ti))]++)] = ti;
    try {
      index.on_a[t] = corner_barycentrics(o, a.F, Side::kA, ti);
      index.on_b[t] = corner_barycentrics(o, b.F, Side::kB, ti);
    } catch (const PipelineError& e) {  // a corner recorded in a face that does not touch the triangle's
      not_this_pair("triangle " + std::to_string(t) + ": " + e.what());
    }
  }
  return index;
}

/// Barycentric coordinates of p with respect to the triangle (c0, c1, c2) of the plane; false if it is degenerate.
bool barycentric_2d(const Eigen::Vector2d& p, const Eigen::Vector2d& c0, const Eigen::Vector2d& c1,
                    const Eigen::Vector2d& c2, Weights& w) {
  const Eigen::Vector2d e1 = c1 - c0, e2 = c2 - c0, d = p - c0;
  const double det = e1.x() * e2.y() - e1.y() * e2.x();
  if (det == 0 || !std::isfinite(det)) return false;
  w[1] = (d.x() * e2.y() - d.y() * e2.x()) / det;
  w[2] = (e1.x() * d.y() - e1.y() * d.x()) / det;
  w[0] = 1.0 - w[1] - w[2];
  return true;
}

/// Point of A (face, barycentric coordinates) of the point of face `fb` of B with barycentric coordinates `beta`:
/// the overlay triangle of fb that contains it (the one with the largest smallest coordinate, so that points on
/// shared edges and rounding outside every triangle still find one), and its affine map onto A.
std::pair<int, Weights> point_on_a(const Overlay& o, const OverlayIndex& index, int fb, const Weights& beta) {
  const Eigen::Vector2d p(beta[1], beta[2]);  // the face's barycentric plane, in its last two coordinates
  int best = -1;
  double best_min = -std::numeric_limits<double>::infinity();
  Weights best_lambda{};
  for (int i = index.start[static_cast<size_t>(fb)]; i < index.start[static_cast<size_t>(fb) + 1]; ++i) {
    const int t = index.triangles[static_cast<size_t>(i)];
    const Corners& c = index.on_b[static_cast<size_t>(t)];
    Weights lambda{};
    if (!barycentric_2d(p, {c[0][1], c[0][2]}, {c[1][1], c[1][2]}, {c[2][1], c[2][2]}, lambda)) continue;
    const double m = std::min({lambda[0], lambda[1], lambda[2]});
    if (m > best_min) {
      best_min = m;
      best = t;
      best_lambda = lambda;
    }
  }
  assert(best >= 0 && "check_every_face_covered has found one");
  const Weights lambda = clamp_barycentric(best_lambda);
  const Corners& c = index.on_a[static_cast<size_t>(best)];
  Weights alpha{0, 0, 0};
  for (size_t k = 0; k < 3; ++k)
    for (size_t j = 0; j < 3; ++j) alpha[j] += lambda[k] * c[k][j];
  return {o.face_a(best), alpha};
}

/// Every face of B holds an overlay triangle of non-zero area, so that point_on_a finds one (checked before the
/// parallel loop, which must not throw).
void check_every_face_covered(const OverlayIndex& index) {
  for (size_t f = 0; f + 1 < index.start.size(); ++f) {
    bool covered = false;
    for (int i = index.start[f]; i < index.start[f + 1] && !covered; ++i) {
      const Corners& c = index.on_b[static_cast<size_t>(index.triangles[static_cast<size_t>(i)])];
      Weights unused{};
      covered = barycentric_2d({c[0][1], c[0][2]}, {c[0][1], c[0][2]}, {c[1][1], c[1][2]}, {c[2][1], c[2][2]}, unused);
    }
    if (!covered) not_this_pair("no overlay triangle of non-zero area lies in face " + std::to_string(f) + " of B");
  }
}

/// A face's UV corners in texel units: x right, y down, texel centres at half-integers.
std::array<Eigen::Vector2d, 3> texel_corners(const TexturedMesh& m, int f, int width, int height) {
  std::array<Eigen::Vector2d, 3> c;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Index i = m.FT(f, k);
    c[static_cast<size_t>(k)] = {m.UV(i, 0) * width, (1.0 - m.UV(i, 1)) * height};
  }
  return c;
}

/// The texels [first, last] of a row or column of n whose centres (i + 0.5) lie in [lo, hi]; empty if none (UVs far
/// outside the image are clamped before they become integers).
std::pair<int, int> texel_range(double lo, double hi, int n) {
  const double first = std::clamp(std::ceil(lo - 0.5), 0.0, static_cast<double>(n));
  const double last = std::clamp(std::floor(hi - 0.5), -1.0, static_cast<double>(n - 1));
  return {static_cast<int>(first), static_cast<int>(last)};
}

/// The faces of B's layout whose texel-space bounding box meets each row of texel centres.
std::vector<std::vector<int>> faces_per_row(const TexturedMesh& b, int width, int height) {
  std::vector<std::vector<int>> rows(static_cast<size_t>(height));
  for (int f = 0; f < static_cast<int>(b.F.rows()); ++f) {
    const auto c = texel_corners(b, f, width, height);
    const double y0 = std::min({c[0].y(), c[1].y(), c[2].y()}), y1 = std::max({c[0].y(), c[1].y(), c[2].y()});
    const auto [first, last] = texel_range(y0, y1, height);
    for (int y = first; y <= last; ++y) rows[static_cast<size_t>(y)].push_back(f);
  }
  return rows;
}

/// Bakes the chart texels of row y.
void bake_row(int y, const std::vector<int>& faces, const Overlay& o, const OverlayIndex& index, const TexturedMesh& a,
              const Image& texture, const TexturedMesh& b, const BakeSettings& s, BakeResult& r) {
  const int width = r.image.width;
  for (const int fb : faces) {
    const auto c = texel_corners(b, fb, width, r.image.height);
    const double x0 = std::min({c[0].x(), c[1].x(), c[2].x()}), x1 = std::max({c[0].x(), c[1].x(), c[2].x()});
    const auto [first, last] = texel_range(x0, x1, width);
    for (int x = first; x <= last; ++x) {
      TexelKind& kind = r.kind[static_cast<size_t>(y) * width + x];
      Weights beta{};
      if (kind == TexelKind::kChart || !barycentric_2d({x + 0.5, y + 0.5}, c[0], c[1], c[2], beta)) continue;
      if (std::min({beta[0], beta[1], beta[2]}) < -1e-12) continue;
      const auto [fa, alpha] = point_on_a(o, index, fb, clamp_barycentric(beta));
      Eigen::Vector2d uv = Eigen::Vector2d::Zero();
      for (int k = 0; k < 3; ++k) uv += alpha[static_cast<size_t>(k)] * a.UV.row(a.FT(fa, k)).transpose();
      r.image.set(x, y, sample_bilinear(texture, uv.x(), uv.y(), s.repeat));
      kind = TexelKind::kChart;
    }
  }
}

}  // namespace

Eigen::Vector3d sample_bilinear(const Image& texture, double u, double v, bool repeat) {
  const int w = texture.width, h = texture.height;
  const double x = u * w - 0.5, y = (1.0 - v) * h - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const double tx = x - fx, ty = y - fy;
  const auto wrap = [repeat](double i, int n) {
    if (repeat) {
      const double m = std::fmod(i, static_cast<double>(n));
      return static_cast<int>(m < 0 ? m + n : m);
    }
    return static_cast<int>(std::clamp(i, 0.0, static_cast<double>(n - 1)));
  };
  const int x0 = wrap(fx, w), x1 = wrap(fx + 1, w), y0 = wrap(fy, h), y1 = wrap(fy + 1, h);
  return (1 - ty) * ((1 - tx) * texture.colour(x0, y0) + tx * texture.colour(x1, y0)) +
         ty * ((1 - tx) * texture.colour(x0, y1) + tx * texture.colour(x1, y1));
}

int fill_gutter(Image& image, std::vector<TexelKind>& kind, int rings) {
  const int w = image.width, h = image.height;
  int filled = 0;
  for (int ring = 0; ring < rings; ++ring) {
    const std::vector<TexelKind> before = kind;
    const auto is_filled = [&](int x, int y) {
      return x >= 0 && y >= 0 && x < w && y < h && before[static_cast<size_t>(y) * w + x] != TexelKind::kEmpty;
    };
    std::vector<std::pair<size_t, Eigen::Vector3d>> fills;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        if (before[static_cast<size_t>(y) * w + x] != TexelKind::kEmpty) continue;
        for (const auto& offsets : {std::array<std::array<int, 2>, 4>{{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}},
                                    std::array<std::array<int, 2>, 4>{{{1, 1}, {-1, 1}, {1, -1}, {-1, -1}}}}) {
          Eigen::Vector3d sum = Eigen::Vector3d::Zero();
          int n = 0;
          for (const auto& [dx, dy] : offsets) {
            if (!is_filled(x + dx, y + dy)) continue;
            sum += image.colour(x + dx, y + dy);
            ++n;
          }
          if (n == 0) continue;
          fills.emplace_back(static_cast<size_t>(y) * w + x, sum / n);
          break;
        }
      }
    }
    for (const auto& [i, colour] : fills) {
      image.set(static_cast<int>(i % w), static_cast<int>(i / w), colour);
      kind[i] = TexelKind::kGutter;
    }
    filled += static_cast<int>(fills.size());
  }
  return filled;
}

BakeResult bake_texture(const Overlay& overlay, const TexturedMesh& a, const Image& texture, const TexturedMesh& b,
                        const BakeSettings& settings) {
  if (texture.width <= 0 || texture.height <= 0) throw InvalidInputError("bake_texture: the texture of A is empty");
  if (settings.width < 0 || settings.height < 0 || settings.gutter < 0)
    throw InvalidInputError("bake_texture: negative size or gutter");
  check_layout(a, "A");
  check_layout(b, "B");
  check_overlay_fits(overlay, a, b);
  const OverlayIndex index = index_overlay(overlay, a, b);
  check_every_face_covered(index);
  BakeResult r;
  const int width = settings.width > 0 ? settings.width : texture.width;
  const int height = settings.height > 0 ? settings.height : texture.height;
  r.image = Image(width, height, settings.background);
  r.kind.assign(static_cast<size_t>(width) * height, TexelKind::kEmpty);
  const std::vector<std::vector<int>> rows = faces_per_row(b, width, height);
  // Rows are independent (each writes only its own texels); the thread count is the caller's.
#pragma omp parallel for schedule(dynamic, 4)
  for (int y = 0; y < height; ++y)
    bake_row(y, rows[static_cast<size_t>(y)], overlay, index, a, texture, b, settings, r);
  r.chart_texels = static_cast<int>(std::count(r.kind.begin(), r.kind.end(), TexelKind::kChart));
  r.gutter_texels = fill_gutter(r.image, r.kind, settings.gutter);
  return r;
}

}  // namespace liftmap
