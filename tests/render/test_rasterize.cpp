#include "render/rasterize.h"

#include <gtest/gtest.h>

#include "common/test_meshes.h"
#include "core/errors.h"
#include "render/alignment.h"
#include "render/colour_maps.h"
#include "render/png_util.h"

namespace liftmap {
namespace {

/// An orthographic camera on +z showing [-1,1]^2 of the plane z = 0.
Camera front_camera() {
  Camera camera;
  camera.projection = Projection::kOrthographic;
  camera.eye = Eigen::Vector3d(0, 0, 5);
  camera.half_height = 1.0;
  return camera;
}

/// 100 by 100 pixels, one sample per pixel, no contour lines: pixel counts are exact.
RasterOptions exact_options() {
  RasterOptions options;
  options.width = options.height = 100;
  options.supersampling = 1;
  options.silhouette_width = 0;
  return options;
}

/// The square [-h,h]^2 at height z as two triangles.
void square(double h, double z, Eigen::MatrixXd& V, Eigen::MatrixXi& F) {
  V.resize(4, 3);
  V << -h, -h, z, h, -h, z, h, h, z, -h, h, z;
  F.resize(2, 3);
  F << 0, 1, 2, 0, 2, 3;
}

bool is(const Image& image, int x, int y, const Eigen::Vector3d& c, int tolerance = 2) {
  for (int k = 0; k < 3; ++k)
    if (std::abs(int(image.pixel(x, y)[k]) - int(to_byte(c[k]))) > tolerance) return false;
  return true;
}

TEST(RenderRasterize, SingleTriangleCoverageAndGouraudColours) {
  Eigen::MatrixXd V(3, 3);
  V << -0.5, -0.5, 0, 0.5, -0.5, 0, -0.5, 0.5, 0;
  const Eigen::MatrixXi F = (Eigen::MatrixXi(1, 3) << 0, 1, 2).finished();
  const Eigen::MatrixXd C = Eigen::MatrixXd::Identity(3, 3);  // red, green, blue corners
  const Image image = rasterize(V, F, C, front_camera(), {}, exact_options());
  // Pixel centres (i + 1/2, j + 1/2) with 25 <= i <= j <= 74: the legs lie on pixel boundaries and the
  // hypotenuse through pixel centres, which count as covered.
  EXPECT_EQ(testing::count_non_background(image, Eigen::Vector3d::Ones(), 0), 50 * 51 / 2);
  EXPECT_TRUE(is(image, 25, 74, Eigen::Vector3d(0.99, 0.0, 0.0), 3));       // next to the red corner
  EXPECT_TRUE(is(image, 74, 74, Eigen::Vector3d(0.0, 0.98, 0.02), 6));      // next to the green corner
  EXPECT_TRUE(is(image, 25, 25, Eigen::Vector3d(0.0, 0.02, 0.98), 6));      // next to the blue corner
  EXPECT_TRUE(is(image, 41, 58, Eigen::Vector3d(1.0, 1.0, 1.0) / 3.0, 4));  // centroid (-1/6, -1/6)
}

TEST(RenderRasterize, SquareCoversItsPixelsOnce) {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  square(0.5, 0.0, V, F);
  const Eigen::MatrixXd C = Eigen::RowVector3d(0.2, 0.4, 0.6).replicate(4, 1);
  for (const int s : {1, 3}) {
    RasterOptions options = exact_options();
    options.supersampling = s;
    const Image image = rasterize(V, F, C, front_camera(), {}, options);
    EXPECT_EQ(testing::count_non_background(image, Eigen::Vector3d::Ones(), 0), 50 * 50) << "supersampling " << s;
    // Facing the headlight: ambient + diffuse = 1, the colour itself.
    EXPECT_TRUE(is(image, 50, 50, Eigen::Vector3d(0.2, 0.4, 0.6), 1));
  }
}

TEST(RenderRasterize, NearerTriangleWinsInEitherOrder) {
  for (const Projection projection : {Projection::kOrthographic, Projection::kPerspective}) {
    Eigen::MatrixXd far_v, near_v;
    Eigen::MatrixXi far_f, near_f;
    square(0.6, 0.0, far_v, far_f);
    square(0.3, 0.5, near_v, near_f);
    for (const bool near_first : {false, true}) {
      Eigen::MatrixXd V(8, 3);
      V << (near_first ? near_v : far_v), (near_first ? far_v : near_v);
      Eigen::MatrixXi F(4, 3);
      F << far_f, (far_f.array() + 4).matrix();
      Eigen::MatrixXd C(8, 3);
      C.topRows(4) = Eigen::RowVector3d(near_first ? 0 : 1, 0, near_first ? 1 : 0).replicate(4, 1);
      C.bottomRows(4) = Eigen::RowVector3d(near_first ? 1 : 0, 0, near_first ? 0 : 1).replicate(4, 1);
      Camera camera = front_camera();
      camera.projection = projection;
      camera.fov_y_degrees = 2.0 * std::atan(1.0 / 5.0) * 180.0 / 3.14159265358979;
      const Image image = rasterize(V, F, C, camera, {}, exact_options());
      // Near square blue, far square red; the centre shows the near one, a corner region the far one.
      EXPECT_GT(image.pixel(50, 50)[2], 200);
      EXPECT_LT(image.pixel(50, 50)[0], 30);
      EXPECT_GT(image.pixel(25, 50)[0], 200);
      EXPECT_LT(image.pixel(25, 50)[2], 30);
    }
  }
}

TEST(RenderRasterize, OverlaysAreDepthTested) {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  square(0.5, 0.0, V, F);
  const Eigen::MatrixXd C = Eigen::RowVector3d(0.5, 0.5, 0.5).replicate(4, 1);
  SurfaceOverlays overlays;
  // On the surface (drawn), and behind it (hidden where the square covers it, drawn outside).
  overlays.polylines.push_back((Eigen::MatrixXd(2, 3) << -0.4, 0.29, 0.0, 0.4, 0.29, 0.0).finished());
  overlays.polylines.push_back((Eigen::MatrixXd(2, 3) << -0.9, -0.31, -1.0, 0.9, -0.31, -1.0).finished());
  overlays.points = (Eigen::MatrixXd(2, 3) << 0.0, 0.0, 0.0, 0.3, 0.0, -1.0).finished();
  overlays.point_colours = (Eigen::MatrixXd(2, 3) << 0, 0, 1, 1, 0, 0).finished();
  const Image image = rasterize(V, F, C, front_camera(), overlays, exact_options());
  const Eigen::Vector3d grey(0.5, 0.5, 0.5);
  EXPECT_TRUE(is(image, 50, 35, overlays.polyline_colour, 2));  // line on the square at y = 0.3
  EXPECT_TRUE(is(image, 50, 65, grey));                         // line behind the square: hidden
  EXPECT_TRUE(is(image, 10, 65, overlays.polyline_colour, 2));  // ... but visible beside it
  EXPECT_TRUE(is(image, 50, 50, Eigen::Vector3d(0, 0, 1), 1));  // dot on the surface, its own colour at the centre
  EXPECT_TRUE(is(image, 65, 50, grey));                         // dot behind the surface: hidden
  // The dark outline ring of the visible dot.
  const int ring_x = 50 + static_cast<int>(overlays.point_radius) - 1;
  EXPECT_LT(image.pixel(ring_x, 50)[0], 80);
}

TEST(RenderRasterize, CamelCoversPlausibleFraction) {
  const TriangleMesh mesh = testing::read_demo_mesh("camel.off");
  ASSERT_GT(mesh.V.rows(), 0);
  const ViewDirection view = default_view(mesh.V, Eigen::MatrixXd());
  RasterOptions options;
  options.width = options.height = 400;
  options.supersampling = 2;
  const Camera camera = fit_camera(mesh.V, view.direction, view.up, 1.0);
  const CheckerTexture texture = make_checker_texture(mesh.V);
  const Image image = rasterize(mesh.V, mesh.F, mesh.V, texture, camera, {}, options);
  const double fraction = testing::count_non_background(image, options.background) / (400.0 * 400.0);
  EXPECT_GT(fraction, 0.1);
  EXPECT_LT(fraction, 0.8);
  // Framed: the border rows and columns are background.
  for (int i = 0; i < 400; ++i) {
    EXPECT_TRUE(is(image, i, 0, options.background, 0));
    EXPECT_TRUE(is(image, 0, i, options.background, 0));
  }
  write_png(testing::output_path("camel_textured.png"), image);
}

TEST(RenderRasterize, EveryTestMeshIsFramedFromItsDefaultView) {
  for (const char* name : testing::kGenusZeroMeshes) {
    const TriangleMesh mesh = testing::read_demo_mesh(name);
    ASSERT_GT(mesh.V.rows(), 0) << name;
    const ViewDirection view = default_view(mesh.V, Eigen::MatrixXd());
    RasterOptions options;
    options.width = 160;
    options.height = 120;
    options.supersampling = 1;
    const Camera camera = fit_camera(mesh.V, view.direction, view.up, 160.0 / 120.0, Projection::kPerspective, 0.9);
    const Image image =
        rasterize(mesh.V, mesh.F, sequential_colours(mesh.V.col(1), mesh.V.col(1).minCoeff(), mesh.V.col(1).maxCoeff()),
                  camera, {}, options);
    // 0.9 of the width or height is spanned: the mesh touches neither border, and covers a fair part.
    int first_x = 160, last_x = -1, first_y = 120, last_y = -1, covered = 0;
    for (int y = 0; y < 120; ++y)
      for (int x = 0; x < 160; ++x)
        if (!is(image, x, y, options.background, 0)) {
          ++covered;
          first_x = std::min(first_x, x);
          last_x = std::max(last_x, x);
          first_y = std::min(first_y, y);
          last_y = std::max(last_y, y);
        }
    EXPECT_GT(covered, 160 * 120 / 12) << name;
    EXPECT_GT(first_x, 0) << name;
    EXPECT_LT(last_x, 159) << name;
    EXPECT_GT(first_y, 0) << name;
    EXPECT_LT(last_y, 119) << name;
    EXPECT_TRUE(last_x - first_x >= 0.85 * 160 || last_y - first_y >= 0.85 * 120) << name;
  }
}

TEST(RenderRasterize, RejectsBadInput) {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  square(0.5, 0.0, V, F);
  EXPECT_THROW(rasterize(V, F, Eigen::MatrixXd(3, 3), front_camera()), InvalidInputError);
  Eigen::MatrixXi bad = F;
  bad(0, 0) = 7;
  EXPECT_THROW(rasterize(V, bad, V, front_camera()), InvalidInputError);
  EXPECT_THROW(rasterize(V, F, V, SolidTexture(), front_camera()), InvalidInputError);
}

}  // namespace
}  // namespace liftmap
