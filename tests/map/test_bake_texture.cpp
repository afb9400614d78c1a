#include "map/bake_texture.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <numbers>
#include <random>
#include <set>

#include "core/errors.h"

namespace liftmap {
namespace {

/// The octahedron with every face split into four `levels` times (positions stay dyadic: a rotation by 90 degrees
/// about z maps vertices exactly onto vertices).
TexturedMesh subdivided_octahedron(int levels) {
  TexturedMesh m;
  m.V.resize(6, 3);
  m.V << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
  m.F.resize(8, 3);
  m.F << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    std::vector<Eigen::RowVector3d> points;
    for (Eigen::Index i = 0; i < m.V.rows(); ++i) points.emplace_back(m.V.row(i));
    const auto midpoint = [&](int i, int j) {
      const auto key = std::minmax(i, j);
      const auto [it, fresh] = mid.emplace(key, static_cast<int>(points.size()));
      if (fresh) points.push_back(0.5 * (points[static_cast<size_t>(i)] + points[static_cast<size_t>(j)]));
      return it->second;
    };
    Eigen::MatrixXi F(4 * m.F.rows(), 3);
    for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
      const int a = m.F(f, 0), b = m.F(f, 1), c = m.F(f, 2);
      const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      F.row(4 * f) << a, ab, ca;
      F.row(4 * f + 1) << ab, b, bc;
      F.row(4 * f + 2) << ca, bc, c;
      F.row(4 * f + 3) << ab, bc, ca;
    }
    m.F = F;
    m.V.resize(static_cast<Eigen::Index>(points.size()), 3);
    for (size_t i = 0; i < points.size(); ++i) m.V.row(static_cast<Eigen::Index>(i)) = points[i];
  }
  return m;
}

/// A "triangle soup" atlas: face f's chart is a right triangle in grid cell `cell_of[f]`, `pad` texels from the
/// cell's sides, its corners rotated by `shift` (so two atlases made with different cells and shifts differ).
void soup_atlas(TexturedMesh& m, int size, int pad, const std::vector<int>& cell_of, int shift) {
  const auto n = static_cast<int>(m.F.rows());
  const int columns = static_cast<int>(std::ceil(std::sqrt(n)));
  const double cell = 1.0 / columns, p = static_cast<double>(pad) / size;
  m.UV.resize(3 * n, 2);
  m.FT.resize(n, 3);
  for (int f = 0; f < n; ++f) {
    const int c = cell_of[static_cast<size_t>(f)];
    const double u0 = (c % columns) * cell, v0 = (c / columns) * cell;
    const Eigen::RowVector2d corners[3] = {{u0 + p, v0 + p}, {u0 + cell - p, v0 + p}, {u0 + p, v0 + cell - p}};
    for (int k = 0; k < 3; ++k) {
      m.UV.row(3 * f + k) = corners[(k + shift) % 3];
      m.FT(f, k) = 3 * f + k;
    }
  }
}

/// A smooth RGB function of the texture coordinates.
Eigen::Vector3d smooth(double u, double v) {
  const double pi = std::numbers::pi;
  return {0.5 + 0.4 * std::sin(2 * pi * u) * std::cos(2 * pi * v), 0.5 + 0.4 * std::cos(2 * pi * (u + v)),
          0.2 + 0.6 * u * v};
}

Image smooth_texture(int size) {
  Image image(size, size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) image.set(x, y, smooth((x + 0.5) / size, 1.0 - (y + 0.5) / size));
  return image;
}

/// Index of the vertex of `m` at position p (exact: positions are dyadic).
int vertex_at(const TexturedMesh& m, const Eigen::RowVector3d& p) {
  for (Eigen::Index i = 0; i < m.V.rows(); ++i)
    if (m.V.row(i) == p) return static_cast<int>(i);
  return -1;
}

/// The map of A onto B = A rotated by `quarter_turns` * 90 degrees about z: the image of A's vertex v is B's vertex
/// rotation[v]; face_of[f] is B's face with the images of A's face f's vertices, image_corner[f][k] the corner of it
/// that is the image of corner k.
struct Rotation {
  std::vector<int> image, face_of;
  std::vector<std::array<int, 3>> image_corner;
};

Rotation rotation_map(const TexturedMesh& m, int quarter_turns) {
  Rotation r;
  for (Eigen::Index v = 0; v < m.V.rows(); ++v) {
    Eigen::RowVector3d p = m.V.row(v);
    for (int q = 0; q < quarter_turns; ++q) p = Eigen::RowVector3d(-p.y(), p.x(), p.z());
    r.image.push_back(vertex_at(m, p));
  }
  std::map<std::set<int>, int> face_of_set;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) face_of_set[{m.F(f, 0), m.F(f, 1), m.F(f, 2)}] = static_cast<int>(f);
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    std::array<int, 3> img{};
    for (int k = 0; k < 3; ++k) img[static_cast<size_t>(k)] = r.image[static_cast<size_t>(m.F(f, k))];
    const int g = face_of_set.at({img[0], img[1], img[2]});
    r.face_of.push_back(g);
    std::array<int, 3> corner{};
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j)
        if (m.F(g, j) == img[static_cast<size_t>(k)]) corner[static_cast<size_t>(k)] = j;
    r.image_corner.push_back(corner);
  }
  return r;
}

/// A face point of `m` at vertex v, recorded in the first face that holds it (so mostly not the overlay triangle's
/// own face: corner_barycentrics must re-express it).
SurfacePoint vertex_point(const TexturedMesh& m, int v) {
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (m.F(f, k) == v) {
        std::array<double, 3> b{0, 0, 0};
        b[static_cast<size_t>(k)] = 1;
        return SurfacePoint::in_face(FaceId(static_cast<int>(f)), b);
      }
  return {};
}

/// The midpoint of edge (i, j) of `m`, recorded in the face on the other side of the edge from face `not_f`.
SurfacePoint edge_midpoint(const TexturedMesh& m, int i, int j, int not_f) {
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    if (f == not_f) continue;
    std::array<double, 3> b{0, 0, 0};
    int found = 0;
    for (int k = 0; k < 3; ++k)
      if (m.F(f, k) == i || m.F(f, k) == j) {
        b[static_cast<size_t>(k)] = 0.5;
        ++found;
      }
    if (found == 2) return SurfacePoint::in_face(FaceId(static_cast<int>(f)), b);
  }
  return {};
}

Eigen::RowVector3d position(const TexturedMesh& m, const SurfacePoint& p) {
  Eigen::RowVector3d x = Eigen::RowVector3d::Zero();
  for (int k = 0; k < 3; ++k) x += p.bary[static_cast<size_t>(k)] * m.V.row(m.F(p.face.idx, k));
  return x;
}

/// The overlay of the rotation map with every face of A split into four at its edge midpoints (the map is affine
/// on each piece), every vertex duplicated per face and recorded in a neighbouring face where it can be.
Overlay rotation_overlay(const TexturedMesh& a, const TexturedMesh& b, const Rotation& r) {
  Overlay o;
  const auto n = static_cast<int>(a.F.rows());
  o.F.resize(4 * n, 3);
  o.face_a.resize(4 * n);
  o.face_b.resize(4 * n);
  for (int f = 0; f < n; ++f) {
    const std::array<int, 3> v{a.F(f, 0), a.F(f, 1), a.F(f, 2)};
    const std::array<int, 3> w{b.F(r.face_of[f], 0), b.F(r.face_of[f], 1), b.F(r.face_of[f], 2)};
    const auto& c = r.image_corner[static_cast<size_t>(f)];
    for (int k = 0; k < 3; ++k) {
      o.on_a.push_back(vertex_point(a, v[static_cast<size_t>(k)]));
      o.on_b.push_back(vertex_point(b, w[static_cast<size_t>(c[static_cast<size_t>(k)])]));
    }
    for (int k = 0; k < 3; ++k) {
      const size_t k1 = static_cast<size_t>(k), k2 = static_cast<size_t>((k + 1) % 3);
      o.on_a.push_back(edge_midpoint(a, v[k1], v[k2], f));
      o.on_b.push_back(edge_midpoint(b, w[static_cast<size_t>(c[k1])], w[static_cast<size_t>(c[k2])], r.face_of[f]));
    }
    const int s = 6 * f;  // corners s, s+1, s+2; midpoints of (0,1), (1,2), (2,0) at s+3, s+4, s+5
    o.F.row(4 * f) << s, s + 3, s + 5;
    o.F.row(4 * f + 1) << s + 3, s + 1, s + 4;
    o.F.row(4 * f + 2) << s + 5, s + 4, s + 2;
    o.F.row(4 * f + 3) << s + 3, s + 4, s + 5;
    for (int t = 4 * f; t < 4 * f + 4; ++t) {
      o.face_a(t) = f;
      o.face_b(t) = r.face_of[static_cast<size_t>(f)];
    }
  }
  o.VA.resize(static_cast<Eigen::Index>(o.on_a.size()), 3);
  o.VB.resize(o.VA.rows(), 3);
  for (Eigen::Index i = 0; i < o.VA.rows(); ++i) {
    o.VA.row(i) = position(a, o.on_a[static_cast<size_t>(i)]);
    o.VB.row(i) = position(b, o.on_b[static_cast<size_t>(i)]);
  }
  return o;
}

/// A's texture coordinates at the point of A that the rotation maps to the point of B's face g with barycentric
/// coordinates beta.
Eigen::Vector2d uv_on_a(const TexturedMesh& a, const Rotation& r, int g, const std::array<double, 3>& beta) {
  const auto f = static_cast<int>(std::find(r.face_of.begin(), r.face_of.end(), g) - r.face_of.begin());
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  for (int k = 0; k < 3; ++k) {
    const double alpha = beta[static_cast<size_t>(r.image_corner[static_cast<size_t>(f)][static_cast<size_t>(k)])];
    uv += alpha * a.UV.row(a.FT(f, k)).transpose();
  }
  return uv;
}

/// Largest difference of one channel, in units of 1/255.
double channel_error(const Eigen::Vector3d& x, const Eigen::Vector3d& y) { return 255 * (x - y).cwiseAbs().maxCoeff(); }

constexpr int kSize = 256;  // texels of both textures
constexpr int kPad = 5;     // texels between a chart and its grid cell's sides

struct Pair {
  TexturedMesh a, b;
  Rotation rotation;
  Overlay overlay;
  Image texture = smooth_texture(kSize);
};

/// A = subdivided octahedron with one soup atlas, B = the same mesh with cells in reverse order and corners
/// shifted, the map a quarter turn.
Pair rotated_pair(int quarter_turns) {
  Pair p;
  p.a = subdivided_octahedron(2);
  p.b = p.a;
  const auto n = static_cast<int>(p.a.F.rows());
  std::vector<int> cells(static_cast<size_t>(n)), reversed(static_cast<size_t>(n));
  for (int f = 0; f < n; ++f) {
    cells[static_cast<size_t>(f)] = f;
    reversed[static_cast<size_t>(f)] = n - 1 - f;
  }
  soup_atlas(p.a, kSize, kPad, cells, 0);
  soup_atlas(p.b, kSize, kPad, reversed, 1);
  p.rotation = rotation_map(p.a, quarter_turns);
  p.overlay = rotation_overlay(p.a, p.b, p.rotation);
  return p;
}

/// Face of B's layout whose chart contains texel (x, y)'s centre, and the centre's barycentric coordinates.
std::pair<int, std::array<double, 3>> texel_point(const TexturedMesh& b, int x, int y) {
  const Eigen::Vector2d p((x + 0.5) / kSize, 1.0 - (y + 0.5) / kSize);
  for (Eigen::Index g = 0; g < b.F.rows(); ++g) {
    const Eigen::Vector2d c0 = b.UV.row(b.FT(g, 0)), c1 = b.UV.row(b.FT(g, 1)), c2 = b.UV.row(b.FT(g, 2));
    Eigen::Matrix2d M;
    M << c1 - c0, c2 - c0;
    const Eigen::Vector2d l = M.inverse() * (p - c0);
    if (l.minCoeff() >= -1e-9 && l.sum() <= 1 + 1e-9) return {static_cast<int>(g), {1 - l.sum(), l.x(), l.y()}};
  }
  return {-1, {}};
}

TEST(BakeTexture, TexelsOfBHoldATextureAtTheirImageOnA) {
  const Pair p = rotated_pair(1);
  const BakeResult r = bake_texture(p.overlay, p.a, p.texture, p.b);
  ASSERT_EQ(r.image.width, kSize);
  int checked = 0;
  double worst_exact = 0, worst_smooth = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const auto [g, beta] = texel_point(p.b, x, y);
      const TexelKind kind = r.kind[static_cast<size_t>(y) * kSize + x];
      if (g < 0) {
        EXPECT_NE(kind, TexelKind::kChart) << x << ", " << y;
        continue;
      }
      ASSERT_EQ(kind, TexelKind::kChart) << x << ", " << y;
      const Eigen::Vector2d uv = uv_on_a(p.a, p.rotation, g, beta);
      worst_exact =
          std::max(worst_exact, channel_error(r.image.colour(x, y), sample_bilinear(p.texture, uv.x(), uv.y(), true)));
      worst_smooth = std::max(worst_smooth, channel_error(r.image.colour(x, y), smooth(uv.x(), uv.y())));
      ++checked;
    }
  EXPECT_EQ(checked, r.chart_texels);
  EXPECT_GT(checked, 5000);
  // Rounding to bytes only: the bake evaluates the same bilinear sample at the same point of A.
  EXPECT_LE(worst_exact, 0.5 + 1e-6);
  // Against the smooth function: two roundings to bytes and bilinear interpolation (|f''| h^2 / 8, about 0.03).
  EXPECT_LE(worst_smooth, 1.1);
  std::printf("chart texels %d, max error vs bilinear sample %.3f/255, vs the smooth function %.3f/255\n", checked,
              worst_exact, worst_smooth);
}

TEST(BakeTexture, ReadBackThroughBsUvsMatchesAAtTheSamePoints) {
  const Pair p = rotated_pair(3);
  const BakeResult r = bake_texture(p.overlay, p.a, p.texture, p.b);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0, 1);
  double worst_inner = 0, worst_all = 0, sum = 0;
  int n = 0;
  for (Eigen::Index g = 0; g < p.b.F.rows(); ++g)
    for (int s = 0; s < 50; ++s) {
      double b1 = unit(random), b2 = unit(random);
      if (b1 + b2 > 1) std::tie(b1, b2) = std::pair(1 - b1, 1 - b2);
      const std::array<double, 3> beta{1 - b1 - b2, b1, b2};
      Eigen::Vector2d uv_b = Eigen::Vector2d::Zero();
      for (int k = 0; k < 3; ++k) uv_b += beta[static_cast<size_t>(k)] * p.b.UV.row(p.b.FT(g, k)).transpose();
      const Eigen::Vector2d uv_a = uv_on_a(p.a, p.rotation, static_cast<int>(g), beta);
      const double e = channel_error(sample_bilinear(r.image, uv_b.x(), uv_b.y(), false), smooth(uv_a.x(), uv_a.y()));
      // Distance in texels from the chart's border: beyond sqrt(2) the four bilinear taps are all chart texels.
      const double legs = kSize / std::ceil(std::sqrt(p.b.F.rows())) - 2 * kPad;
      const double border = std::min({b1, b2, 1 - b1 - b2}) * legs / std::sqrt(2.0);  // a lower bound
      if (border > 1.5) worst_inner = std::max(worst_inner, e);
      worst_all = std::max(worst_all, e);
      sum += e;
      ++n;
    }
  std::printf("%d points read back through B's UVs: max error %.2f/255 inside charts, %.2f/255 anywhere, mean %.2f\n",
              n, worst_inner, worst_all, sum / n);
  EXPECT_LE(worst_inner, 1.5);
  EXPECT_LE(worst_all, 5.0) << "near a border the gutter repeats the border texels: one texel of gradient";
  EXPECT_LE(sum / n, 0.6);
}

TEST(BakeTexture, SameAtlasAndIdentityGiveTheTextureBack) {
  Pair p = rotated_pair(0);
  p.b = p.a;
  p.overlay = rotation_overlay(p.a, p.b, p.rotation);
  const BakeResult r = bake_texture(p.overlay, p.a, p.texture, p.b);
  int differ = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      if (r.kind[static_cast<size_t>(y) * kSize + x] == TexelKind::kChart &&
          !std::equal(r.image.pixel(x, y), r.image.pixel(x, y) + 3, p.texture.pixel(x, y)))
        ++differ;
  EXPECT_EQ(differ, 0) << "texel centres of B are A's: the bilinear sample is the texel itself";
}

/// Chessboard distance of every texel to the nearest chart texel (breadth-first over the 8-neighbourhood).
std::vector<int> distance_to_charts(const std::vector<TexelKind>& kind, int w, int h) {
  std::vector<int> d(kind.size(), -1);
  std::deque<int> queue;
  for (size_t i = 0; i < kind.size(); ++i)
    if (kind[i] == TexelKind::kChart) {
      d[i] = 0;
      queue.push_back(static_cast<int>(i));
    }
  while (!queue.empty()) {
    const int i = queue.front();
    queue.pop_front();
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int x = i % w + dx, y = i / w + dy;
        if (x < 0 || y < 0 || x >= w || y >= h || d[static_cast<size_t>(y * w + x)] >= 0) continue;
        d[static_cast<size_t>(y * w + x)] = d[static_cast<size_t>(i)] + 1;
        queue.push_back(y * w + x);
      }
  }
  return d;
}

TEST(BakeTexture, GutterFillsTheRingsAroundChartsAndNothingFarther) {
  const Pair p = rotated_pair(1);
  BakeSettings settings;
  settings.gutter = 3;
  settings.background = Eigen::Vector3d(1, 0, 1);
  const BakeResult r = bake_texture(p.overlay, p.a, p.texture, p.b, settings);
  const std::vector<int> d = distance_to_charts(r.kind, kSize, kSize);
  int far = 0;
  double worst = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const size_t i = static_cast<size_t>(y) * kSize + x;
      if (d[i] >= 1 && d[i] <= settings.gutter) {
        ASSERT_EQ(r.kind[i], TexelKind::kGutter) << x << ", " << y;
        // A gutter texel repeats nearby border colours: within a few texels of gradient of the chart's.
        worst = std::max(worst, channel_error(r.image.colour(x, y), Eigen::Vector3d(1, 0, 1)));
      } else if (d[i] > settings.gutter) {
        ASSERT_EQ(r.kind[i], TexelKind::kEmpty);
        ASSERT_EQ(r.image.colour(x, y), Eigen::Vector3d(1, 0, 1)) << "background left alone at " << x << ", " << y;
        ++far;
      }
    }
  EXPECT_GT(far, 1000) << "the atlas leaves room beyond the gutter";
  EXPECT_GT(r.gutter_texels, 1000);
  EXPECT_GT(worst, 50) << "gutter texels hold the chart's colours, not the magenta background";
  BakeSettings none = settings;
  none.gutter = 0;
  EXPECT_EQ(bake_texture(p.overlay, p.a, p.texture, p.b, none).gutter_texels, 0);
}

TEST(BakeTexture, UvsOutsideTheImageAreNotBaked) {
  Pair p = rotated_pair(1);
  const int before = bake_texture(p.overlay, p.a, p.texture, p.b).chart_texels;
  p.b.UV.row(p.b.FT(0, 0)) << 1e300, -1e300;  // face 0's chart now reaches far beyond the image
  p.b.UV.row(p.b.FT(1, 0)) << 3.0, 0.5;       // face 1's chart partly right of it
  const BakeResult r = bake_texture(p.overlay, p.a, p.texture, p.b);
  EXPECT_GT(r.chart_texels, before / 2);
  EXPECT_LT(r.chart_texels, kSize * kSize);
}

TEST(BakeTexture, SampleBilinearRepeatsOrClamps) {
  Image t(2, 1, Eigen::Vector3d::Zero());
  t.set(1, 0, Eigen::Vector3d::Ones());
  EXPECT_NEAR(sample_bilinear(t, 0.5, 0.5, true).x(), 0.5, 1e-12) << "between the two texel centres";
  EXPECT_NEAR(sample_bilinear(t, 0.0, 0.5, true).x(), 0.5, 1e-12) << "the left edge wraps to the right texel";
  EXPECT_NEAR(sample_bilinear(t, 0.0, 0.5, false).x(), 0.0, 1e-12) << "clamped to the left texel";
  EXPECT_NEAR(sample_bilinear(t, 1.75, 0.5, true).x(), 1.0, 1e-12) << "u = 1.75 repeats u = 0.75";
}

TEST(BakeTexture, AnOverlayOfOtherMeshesIsRejected) {
  const Pair p = rotated_pair(1);
  Overlay wrong_face = p.overlay;
  wrong_face.face_b(5) = static_cast<int>(p.b.F.rows());
  EXPECT_THROW(bake_texture(wrong_face, p.a, p.texture, p.b), InvalidInputError);
  Overlay moved = p.overlay;
  moved.VA(3, 0) += 0.1;
  try {
    bake_texture(moved, p.a, p.texture, p.b);
    FAIL() << "an overlay vertex off its point of A must be rejected";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 3"), std::string::npos) << e.what();
  }
  Overlay elsewhere = p.overlay;  // a corner of triangle 0 recorded on B in a face far from the triangle's
  const int far_face = (p.overlay.face_b(0) + static_cast<int>(p.b.F.rows()) / 2) % static_cast<int>(p.b.F.rows());
  elsewhere.on_b[static_cast<size_t>(elsewhere.F(0, 0))] = SurfacePoint::in_face(FaceId(far_face), {0.2, 0.3, 0.5});
  try {
    bake_texture(elsewhere, p.a, p.texture, p.b);
    FAIL() << "a corner off the triangle's face must be rejected";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 0"), std::string::npos) << e.what();
  }
  Overlay missing = p.overlay;  // the triangles in B's face 0 dropped
  std::vector<int> keep;
  for (Eigen::Index t = 0; t < missing.F.rows(); ++t)
    if (missing.face_b(t) != 0) keep.push_back(static_cast<int>(t));
  missing.F = Eigen::MatrixXi(p.overlay.F(keep, Eigen::all));
  missing.face_a = Eigen::VectorXi(p.overlay.face_a(keep));
  missing.face_b = Eigen::VectorXi(p.overlay.face_b(keep));
  try {
    bake_texture(missing, p.a, p.texture, p.b);
    FAIL() << "a face of B without overlay triangles must be rejected";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("face 0 of B"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace liftmap
