// Chapter 06's spot atlas (spot_atlas.h): the tiles of the grid and the clamped lookup, on the CPU.
#include <gtest/gtest.h>

#include <vector>

#include "chapters/06_shadows/spot_atlas.h"
#include "common/error.h"

using namespace lp;
using namespace lp::ch06;

// Every count from 1 to kMaxSpotShadows: the tiles are equal squares inside the atlas, no two
// share a texel, and they fill the grid g = ceil(sqrt(count)) (one tile alone: the whole atlas).
TEST(SpotAtlas, TilesAreEqualSquaresThatNeverOverlap) {
  constexpr int kSize = 1000;  // not a multiple of 3: the grid's remainder stays unused
  for (int count = 1; count <= kMaxSpotShadows; ++count) {
    int g = 1;
    while (g * g < count) ++g;
    std::vector<int> owner(std::size_t(kSize) * kSize, -1);
    for (int i = 0; i < count; ++i) {
      const AtlasTile t = spot_atlas_tile(i, count, kSize);
      ASSERT_EQ(t.size, kSize / g) << count;
      ASSERT_GE(t.x, 0);
      ASSERT_GE(t.y, 0);
      ASSERT_LE(t.x + t.size, kSize);
      ASSERT_LE(t.y + t.size, kSize);
      EXPECT_FLOAT_EQ(t.corner.x, float(t.x) / kSize);
      EXPECT_FLOAT_EQ(t.corner.y, float(t.y) / kSize);
      EXPECT_FLOAT_EQ(t.side, float(t.size) / kSize);
      for (int y = t.y; y < t.y + t.size; ++y)
        for (int x = t.x; x < t.x + t.size; ++x) {
          int& o = owner[std::size_t(y) * kSize + std::size_t(x)];
          ASSERT_EQ(o, -1) << "tiles " << o << " and " << i << " of " << count << " share texel " << x << ", " << y;
          o = i;
        }
    }
  }
  EXPECT_EQ(spot_atlas_tile(0, 1, 2048).size, 2048);
}

// The lookup stays on the tile's own texels: a tile-local (u, v) past its edge reads the centre
// of the border texel, inside the tile reads where it says.
TEST(SpotAtlas, LookupsAreClampedToTheTilesBorderTexels) {
  const AtlasTile t = spot_atlas_tile(3, 4, 512);  // the upper right of a 2 x 2 grid
  ASSERT_EQ(t.x, 256);
  ASSERT_EQ(t.y, 256);
  auto texel = [](glm::vec2 atlas_uv) { return glm::ivec2(glm::floor(atlas_uv * 512.f)); };
  EXPECT_EQ(texel(spot_atlas_uv(t, {0.5f, 0.5f})), glm::ivec2(384, 384));
  EXPECT_EQ(texel(spot_atlas_uv(t, {-0.2f, 1.3f})), glm::ivec2(256, 511));
  EXPECT_EQ(texel(spot_atlas_uv(t, {1.f + 3.f / 256.f, -3.f / 256.f})), glm::ivec2(511, 256));
  // The clamped lookups land on texel centres, where nearest sampling cannot round across.
  const glm::vec2 low = spot_atlas_uv(t, {-1.f, -1.f}) * 512.f;
  EXPECT_FLOAT_EQ(low.x, 256.5f);
  EXPECT_FLOAT_EQ(low.y, 256.5f);
}

TEST(SpotAtlas, OutOfRangeTilesAreErrors) {
  EXPECT_THROW(spot_atlas_tile(0, 0, 1024), Error);
  EXPECT_THROW(spot_atlas_tile(0, kMaxSpotShadows + 1, 1024), Error);
  EXPECT_THROW(spot_atlas_tile(4, 4, 1024), Error);
  EXPECT_THROW(spot_atlas_tile(-1, 4, 1024), Error);
  EXPECT_THROW(spot_atlas_tile(0, 9, 2), Error);  // a 3 x 3 grid in 2 texels
}
