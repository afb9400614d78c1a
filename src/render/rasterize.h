#pragma once
/// Software z-buffer rasterizer for closed triangle meshes with surface overlays (cut paths, landmarks): the
/// renderer behind render.png, headless and deterministic.

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "render/camera.h"
#include "render/image.h"

namespace liftmap {

/// A colour function of a 3D point (a solid texture), RGB in [0,1]; evaluated once per covered sample.
using SolidTexture = std::function<Eigen::Vector3d(const Eigen::Vector3d&)>;

/// What is drawn on top of the surface, depth-tested against it and pulled toward the camera by
/// RasterOptions::overlay_bias so that it is not buried in the faces it lies on.
struct SurfaceOverlays {
  std::vector<Eigen::MatrixXd> polylines;  ///< each #P by 3, consecutive points joined (e.g. cut paths)
  Eigen::Vector3d polyline_colour{0.12, 0.72, 0.22};
  double polyline_width = 4.0;  ///< in pixels of the output image

  Eigen::MatrixXd points;         ///< #L by 3 positions (e.g. landmarks), drawn as small shaded spheres
  Eigen::MatrixXd point_colours;  ///< #L by 3 RGB in [0,1]; empty: all drawn in red
  double point_radius = 8.0;      ///< in pixels of the output image
  Eigen::Vector3d outline_colour{0.12, 0.12, 0.12};
  double outline_width = 1.5;  ///< dark ring around each point, in pixels of the output image
};

/// Image size, anti-aliasing and lighting.
struct RasterOptions {
  int width = 800;
  int height = 800;
  int supersampling = 3;  ///< s: render s*width by s*height samples, average s by s blocks (1 = no anti-aliasing)
  Eigen::Vector3d background{1.0, 1.0, 1.0};
  double ambient = 0.35;          ///< light everywhere
  double diffuse = 0.65;          ///< Lambert term of a headlight (light at the eye); two-sided
  double specular = 0.0;          ///< white highlight of the headlight (Blinn-Phong), 0: matte
  double shininess = 24.0;        ///< exponent of the highlight
  bool smooth_shading = true;     ///< interpolate area-weighted vertex normals (else face normals)
  double silhouette_width = 1.0;  ///< dark contour where the depth jumps, in output pixels (0: none)
  double overlay_bias = 0.01;     ///< overlays are tested this fraction of V's bounding radius closer to the eye
};

/// Renders a mesh with per-vertex colours interpolated across faces (Gouraud), lit by a headlight.
/// Both sides of every face are drawn (meshes are closed). Faces with a vertex behind the eye are skipped.
/// \param V #V by 3 vertex positions
/// \param F #F by 3 vertex indices
/// \param C #V by 3 per-vertex RGB in [0,1]
/// \throw InvalidInputError for mismatched shapes, indices out of range, or a non-positive image size
Image rasterize(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& C, const Camera& camera,
                const SurfaceOverlays& overlays = {}, const RasterOptions& options = {});

/// Renders a mesh painted with a solid texture evaluated at every sample: the texture coordinates T are
/// interpolated across faces and passed to `texture`. T = V paints a mesh with its own texture; T = g(V), the
/// images of B's vertices on A under a map g, paints B with A's texture pulled back through the map.
/// \param V #V by 3 vertex positions
/// \param F #F by 3 vertex indices
/// \param T #V by 3 texture coordinates (3D points at which `texture` is evaluated)
/// \throw InvalidInputError for mismatched shapes, indices out of range, a non-positive image size or no texture
Image rasterize(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& T,
                const SolidTexture& texture, const Camera& camera, const SurfaceOverlays& overlays = {},
                const RasterOptions& options = {});

}  // namespace liftmap
