#pragma once
// [spot-atlas]
// The marked spot lights share one depth texture, the atlas: a square of `atlas_size` texels cut
// into a grid of equal square tiles, g = ceil(sqrt(count)) a side, tile i at column i mod g and
// row i / g (row 0 at the bottom, as the texture's t). Each spot draws its perspective map
// (shadow_math.h [spot-frustum]) into its tile through the tile's viewport, and a lookup turns
// the map's (u, v) in [0, 1] into the atlas's by the tile's corner and side, clamped to the
// tile's own border texels first: a PCF tap past a tile's edge must not read the next tile.
// Equal tiles, not sizes by screen coverage: a tile's texel stays the same size as the camera
// moves (a size that follows the coverage moves every shadow edge, as an unsnapped cascade does),
// and one spot alone gets the whole atlas.
#include <glm/glm.hpp>

namespace lp::ch06 {

inline constexpr int kMaxSpotShadows = 16;  // spot lights with a tile in one frame (a 4 x 4 grid)

struct AtlasTile {
  int x = 0, y = 0, size = 0;  // the tile's lower-left texel and its side, texels
  glm::vec2 corner{0.f};       // the lower-left corner in the atlas's (u, v)
  float side = 0.f;            // the side in the atlas's (u, v): size / atlas_size
};
// Tile `index` of `count` (1 to kMaxSpotShadows) in an atlas of `atlas_size` texels a side;
// an Error for a count, index or size out of range.
AtlasTile spot_atlas_tile(int index, int count, int atlas_size);
// The atlas's (u, v) that a tile-local (u, v) reads: clamped to the centres of the tile's border
// texels, then placed in the tile (lookup_math.glsl's spot_atlas_uv, its twin).
glm::vec2 spot_atlas_uv(const AtlasTile& tile, glm::vec2 uv);

}  // namespace lp::ch06
// [/spot-atlas]
