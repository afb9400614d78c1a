#include "render/figure.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <functional>
#include <queue>

#include "common/test_meshes.h"
#include "core/errors.h"
#include "render/alignment.h"
#include "render/colour_maps.h"
#include "render/png_util.h"
#include "render/rasterize.h"

namespace liftmap {
namespace {

/// Shortest path along mesh edges from vertex s to vertex t, as a #P by 3 polyline (a stand-in for a cut path).
Eigen::MatrixXd edge_path(const TriangleMesh& mesh, int s, int t) {
  std::vector<std::vector<int>> adjacent(mesh.V.rows());
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) adjacent[mesh.F(f, k)].push_back(mesh.F(f, (k + 1) % 3));
  std::vector<double> dist(mesh.V.rows(), 1e300);
  std::vector<int> from(mesh.V.rows(), -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  dist[s] = 0;
  queue.push({0, s});
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (v == t) break;
    if (d > dist[v]) continue;
    for (const int w : adjacent[v]) {
      const double dw = d + (mesh.V.row(v) - mesh.V.row(w)).norm();
      if (dw < dist[w]) {
        dist[w] = dw;
        from[w] = v;
        queue.push({dw, w});
      }
    }
  }
  std::vector<int> path{t};
  while (path.back() != s) path.push_back(from[path.back()]);
  Eigen::MatrixXd P(path.size(), 3);
  for (std::size_t i = 0; i < path.size(); ++i) P.row(i) = mesh.V.row(path[i]);
  return P;
}

/// The landmarks of examples/camel-cow/landmarks.txt: nose, tail, front left/right, back left/right hooves.
const int kCamel[] = {315, 4248, 9067, 9495, 8802, 9213};
const int kCow[] = {1156, 2334, 771, 2125, 901, 2255};

FigurePanel panel(const TriangleMesh& mesh, const int* landmarks, const std::string& label) {
  FigurePanel p;
  p.V = mesh.V;
  p.F = mesh.F;
  p.label = label;
  p.landmarks.resize(6, 3);
  for (int i = 0; i < 6; ++i) p.landmarks.row(i) = mesh.V.row(landmarks[i]);
  // A tree: nose to tail and to the front hooves, tail to the back hooves.
  for (const auto& [i, j] : {std::pair{0, 1}, {0, 2}, {0, 3}, {1, 4}, {1, 5}})
    p.cut_paths.push_back(edge_path(mesh, landmarks[i], landmarks[j]));
  return p;
}

int count_colour(const Image& image, int x0, int x1, const Eigen::Vector3d& c) {
  int n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = x0; x < x1; ++x) {
      bool same = true;
      for (int k = 0; k < 3; ++k) same = same && std::abs(int(image.pixel(x, y)[k]) - int(to_byte(c[k]))) <= 4;
      n += same;
    }
  return n;
}

TEST(RenderMapFigure, CamelAndCowSideBySide) {
  const TriangleMesh camel = testing::read_demo_mesh("camel.off");
  const TriangleMesh cow = testing::read_demo_mesh("cow.off");
  ASSERT_GT(camel.V.rows(), 0);
  ASSERT_GT(cow.V.rows(), 0);
  const FigurePanel a = panel(camel, kCamel, "A: camel.off");
  FigurePanel b = panel(cow, kCow, "B: cow.off");
  // No map here: B's vertices are sent to their positions after landmark alignment, a stand-in for g(y).
  b.T = align_similarity(a.landmarks, b.landmarks).apply(cow.V);

  MapFigureOptions options;
  options.supersampling = 2;
  const Image image = render_map_figure(a, b, options);
  ASSERT_EQ(image.width, 1600);
  ASSERT_EQ(image.height, 800);
  const std::string path = testing::output_path("camel_cow_figure.png");
  write_png(path, image);
  const testing::PngHeader header = testing::read_png_header(path);
  EXPECT_TRUE(header.signature_ok);
  EXPECT_EQ(header.width, 1600u);
  EXPECT_EQ(header.height, 800u);

  // Both panels show a mesh, the cut paths and most landmarks, each in its own colour.
  const Eigen::MatrixXd colours = landmark_colours(6);
  const SurfaceOverlays defaults;
  for (const auto& [x0, x1] : {std::pair{0, 800}, {800, 1600}}) {
    Image half(800, 800);
    for (int y = 0; y < 800; ++y)
      for (int x = x0; x < x1; ++x) std::copy_n(image.pixel(x, y), 3, half.pixel(x - x0, y));
    const double fraction = testing::count_non_background(half, options.background) / (800.0 * 800.0);
    EXPECT_GT(fraction, 0.08) << "panel at x = " << x0;
    EXPECT_LT(fraction, 0.8) << "panel at x = " << x0;
    EXPECT_GT(count_colour(image, x0, x1, defaults.polyline_colour), 50) << "panel at x = " << x0;
    int seen = 0;
    for (int i = 0; i < 6; ++i) seen += count_colour(image, x0, x1, colours.row(i).transpose()) > 0;
    EXPECT_GE(seen, 4) << "panel at x = " << x0;
  }
}

TEST(RenderMapFigure, MapToItselfGivesTwoEqualPanels) {
  const TriangleMesh cow = testing::read_demo_mesh("cow.off");
  ASSERT_GT(cow.V.rows(), 0);
  // The cow mapped to a moved, scaled copy of itself, both coloured per vertex with A's texture: after the
  // landmark alignment both panels show the same picture.
  FigurePanel a = panel(cow, kCow, "");
  a.C = evaluate_texture(make_checker_texture(cow.V, 6), cow.V);
  FigurePanel b = a;
  SimilarityTransform moved;
  moved.R = Eigen::AngleAxisd(1.0, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  moved.scale = 2.5;
  moved.t = Eigen::Vector3d(10, -3, 2);
  b.V = moved.apply(a.V);
  b.landmarks = moved.apply(a.landmarks);
  for (Eigen::MatrixXd& P : b.cut_paths) P = moved.apply(P);
  MapFigureOptions options;
  options.width = 600;
  options.height = 300;
  options.supersampling = 1;
  options.view = ViewDirection{Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(0, 1, 0)};
  const Image image = render_map_figure(a, b, options);
  write_png(testing::output_path("cow_cow_figure.png"), image);
  int differ = 0, inked = 0;
  for (int y = 0; y < 300; ++y)
    for (int x = 0; x < 300; ++x) {
      const std::uint8_t* l = image.pixel(x, y);
      const std::uint8_t* r = image.pixel(x + 300, y);
      inked += l[0] != 255 || l[1] != 255 || l[2] != 255;
      differ += std::abs(int(l[0]) - int(r[0])) + std::abs(int(l[1]) - int(r[1])) + std::abs(int(l[2]) - int(r[2])) > 6;
    }
  EXPECT_GT(inked, 300 * 300 / 10);
  EXPECT_LT(differ, inked / 200);
}

TEST(RenderMapFigure, RejectsInconsistentPanels) {
  Eigen::MatrixXd V = Eigen::MatrixXd::Random(4, 3);
  Eigen::MatrixXi F(4, 3);
  F << 0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2;
  FigurePanel a{V, F, {}, {}, {}, V.topRows(3), "A"};
  FigurePanel b{V, F, {}, {}, {}, V.topRows(2), "B"};
  EXPECT_THROW(render_map_figure(a, b), InvalidInputError);  // 3 landmarks against 2
  b.landmarks = V.topRows(3);
  EXPECT_THROW(render_map_figure(a, b), InvalidInputError);  // B has neither T nor C
}

}  // namespace
}  // namespace liftmap
