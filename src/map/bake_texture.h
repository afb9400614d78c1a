#pragma once
/// Texture baking through a map (`liftmap transfer texture`, issue 32): A's texture drawn into B's own UV atlas.
///
/// For every texel of B's atlas whose centre lies in a triangle of B's UV layout: the point of B there (a face of B
/// and barycentric coordinates), the overlay triangle of that face containing it, the same affine combination of
/// that triangle's corners on A (the map is affine on every overlay triangle), A's texture coordinates at that point
/// of A, and A's texture there, sampled bilinearly. Texels outside every chart within `gutter` texels of one are then
/// filled ring by ring from their filled neighbours, so that mip-mapping and bilinear filtering do not blend the
/// background into a chart's border.

#include <cstdint>
#include <vector>

#include "core/overlay.h"
#include "io/read_obj_with_uv.h"
#include "render/image.h"

namespace liftmap {

/// Options of bake_texture.
struct BakeSettings {
  int width = 0;   ///< the baked image's width in texels; 0: the source texture's
  int height = 0;  ///< its height; 0: the source texture's
  int gutter = 4;  ///< rings of texels around every chart filled from the chart's border (0: none)
  /// How A's texture is sampled at texture coordinates outside [0,1] and in the outermost half texel: repeated
  /// (OpenGL's GL_REPEAT, what OBJ viewers do by default) or clamped to the edge texels (GL_CLAMP_TO_EDGE).
  bool repeat = true;
  Eigen::Vector3d background = Eigen::Vector3d::Zero();  ///< RGB in [0,1] of the texels neither chart nor gutter
};

/// What each texel of the baked image holds.
enum class TexelKind : std::uint8_t { kEmpty, kChart, kGutter };

/// The baked texture.
struct BakeResult {
  Image image;                  ///< width by height, B's atlas painted with A's texture
  std::vector<TexelKind> kind;  ///< width * height, row-major, top row first, as `image`
  int chart_texels = 0;         ///< texels whose centre is in a triangle of B's UV layout
  int gutter_texels = 0;        ///< texels filled by the gutter
};

/// Bakes A's texture into B's UV atlas through the map whose overlay is `overlay`.
/// Texel (x, y) (x right, y down from the top row) has its centre at u = (x + 0.5) / width,
/// v = 1 - (y + 0.5) / height, the OBJ convention (v up); parts of B's layout outside [0,1]^2 are not baked. A texel
/// centre on an edge shared by two triangles of B's layout, or by two overlay triangles, takes the first triangle
/// found; both give the same point up to rounding. \param overlay the common refinement of A and B (read_overlay),
/// faces of `a.F` and `b.F` \param a mesh A with its UV layout (UV, FT); `texture` is A's image \param b mesh B with
/// its UV layout: the atlas baked into \param settings size, gutter, sampling, background \pre texture is not empty;
/// settings.width, height >= 0 and gutter >= 0 \throw InvalidInputError if the overlay does not belong to A and B: a
/// face of A or B out of range, an overlay
///        vertex whose position on A is not where its face point of A is (1e-6 of A's bounding box), a triangle
///        corner recorded in a face that does not touch the triangle's face, or a face of B
///        in B's layout that no overlay triangle lies in.
BakeResult bake_texture(const Overlay& overlay, const TexturedMesh& a, const Image& texture, const TexturedMesh& b,
                        const BakeSettings& settings = {});

/// Fills, ring by ring, the empty texels next to a filled one (chart or an earlier ring) with the mean of their
/// filled 4-neighbours, or of their filled diagonal neighbours if they have none: after `rings` rings every empty
/// texel within `rings` texels (chessboard distance) of a chart holds a colour of its nearest chart border.
/// \param image width by height; \param kind width * height, as BakeResult::kind; filled texels become kGutter
/// \return the number of texels filled
int fill_gutter(Image& image, std::vector<TexelKind>& kind, int rings);

/// A's texture at texture coordinates (u, v), bilinearly interpolated between the four nearest texel centres,
/// RGB in [0,1]. \param repeat as BakeSettings::repeat \pre texture is not empty
Eigen::Vector3d sample_bilinear(const Image& texture, double u, double v, bool repeat);

}  // namespace liftmap
