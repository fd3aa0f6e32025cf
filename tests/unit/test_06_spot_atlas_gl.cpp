// Chapter 06's spot atlas on the GPU (llvmpipe in CI): several marked spot lights, each drawn
// into its tile of one depth texture (spot_atlas.h), read back as each spot's visibility alone
// (ShadowPicture::SpotVisibility) against one ray per pixel toward the light
// (spot_shadow_truth); and a PCF kernel whose taps cross a tile's edge, which must read that
// tile's own border, whatever the neighbouring tiles hold.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/06_shadows/shadow_stage.h"
#include "chapters/06_shadows/shadow_truth.h"
#include "chapters/06_shadows/spot_atlas.h"
#include "common/paths.h"
#include "common/target.h"
#include "tests/unit/gl_environment.h"
#include "tests/unit/light_edge_band.h"

using namespace lp;
using namespace lp::ch06;

namespace {

constexpr int kW = 320, kH = 180;

Light marked_spot(const std::string& name, glm::vec3 position, glm::vec3 direction, float cone) {
  Light l;
  l.name = name;
  l.type = LightType::Spot;
  l.intensity = 40.f;
  l.position = position;
  l.direction = glm::normalize(direction);
  l.outer_cone = cone, l.inner_cone = 0.8f * cone;
  l.casts_shadows = true;
  return l;
}

// The atrium with `spots` added, every one marked to cast.
struct Atrium {
  explicit Atrium(const std::vector<Light>& spots)
      : scene(load(spots)), gpu(scene), rays(scene), frame(gpu), stage(gpu, find_sun(scene)) {
    frame.volumes().set_lights(ch03::build_light_set(
        scene.lights, ch03::cut_threshold(1.f, ch03::peak_reflectance(scene)), frame.volumes().shapes()));
    frame.add_stage(stage);
  }
  static Scene load(const std::vector<Light>& spots) {
    Scene s = load_scene(from_root("assets/atrium/atrium.gltf"));
    for (const Light& l : spots) s.lights.push_back(l);
    return s;
  }
  FrameCamera camera(const std::string& view) const { return frame_camera(scene.camera(view), float(kW) / kH); }
  // Spot light k's visibility alone, top row first.
  ImageF spot_visibility(const FrameCamera& cam, ShadowSettings s, int k) {
    ColourTarget target(kW, kH, GL_RGBA32F);
    s.spot_shown = k;
    stage.set(s, ShadowPicture::SpotVisibility);
    frame.render(cam, {target.framebuffer(), kW, kH});
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    return target.read();
  }
  Scene scene;
  SceneGpu gpu;
  RayScene rays;
  ch03::DeferredFrame frame;
  ShadowStage stage;
};

// Pixels the rasteriser marks as sky or facing away (blue) where the truth's mask says
// otherwise: the pixel's centre ray and the fragment saw different surfaces (a silhouette).
void exclude_raster_mask(const ImageF& v, std::vector<bool>& exclude) {
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      if (v.at(x, y, 2) > 0.3f && v.at(x, y, 0) < 0.2f) exclude[std::size_t(y) * kW + x] = true;
}

FrameCamera looking_down(glm::vec3 eye) {
  Camera c;
  c.world = glm::inverse(glm::lookAt(eye, eye - glm::vec3(0, 1, 0), glm::vec3(0, 0, -1)));
  return frame_camera(c, float(kW) / kH);
}

// [spot-band]
// The pixels near a shadow edge of spot k's truth, each by its own reach (as the point lights'
// test, test_06_point_shadows_gl.cpp [point-band]): a receiver at distance d from the light, at
// angle theta to it, seen t metres from the eye, may see the tile's edge moved by `texels`
// (half a texel, the biases with its own tan(theta) capped at kMaxSlope, the normal offset,
// PCF's r) of w(d) = 2 d tan(cone) / N each (N: the tile's side), over its pixel's footprint
// t 2 tan(fov / 2) / H. A pixel is in the band when within its count of pixels lies a
// lit/shadowed boundary of the truth, the border of what the light reaches, a crease (neighbours
// whose geometric normals differ: a texel holds one depth), or the image's border.
std::vector<bool> spot_band(const std::vector<std::optional<Hit>>& hits, const ImageF& truth, const Light& l,
                            const SpotFrustum& f, int tile, const FrameCamera& cam, const ShadowSettings& s, int r,
                            int* widest) {
  return light_edge_band(hits, truth, l, cam, s, r, kW, kH, [&](float d) { return f.texel_world(d, tile); },
                          widest);
}
// [/spot-band]

}  // namespace

// [atlas-gl]
// Four marked spots, 2.5 to 3.5 m up in the aisle, each aimed across the floor past columns (the
// single-spot test's light and three others, none a mirror image of another: the atrium repeats
// itself every 3 m and left to right, and a spot's twin would draw the same map): four tiles of
// 1024^2 in a 2048^2 atlas. Each spot's visibility against its ray-traced shadows outside the
// band of the tile's reach, each pixel by its own ([spot-band]), and the probe on the receiver
// (light_edge_band.h [receiver-probe]). Allowed outside them, hard and PCF 3x3: none on the wrong
// side, and no tap wrong (the mean |error| exactly 0). A tile's matrix, viewport or corner taken from another spot puts
// another light's depths under this one's receivers, and the columns' shadows land where the
// truth has none.
TEST(SpotAtlasGl, EverySpotInItsTileMatchesItsRayTracedShadowsOutsideTheBand) {
  const std::vector<Light> spots = {
      marked_spot("spot_a", {1.f, 3.f, 1.5f}, {3.5f, -3.f, 0.f}, 0.8f),
      marked_spot("spot_b", {-1.f, 3.f, 0.5f}, {-3.5f, -3.f, 1.5f}, 0.7f),
      marked_spot("spot_c", {0.5f, 2.5f, 5.f}, {3.f, -3.f, -2.f}, 0.8f),
      marked_spot("spot_d", {-1.5f, 3.5f, 7.f}, {-2.5f, -3.f, -1.f}, 0.9f),
  };
  Atrium w(spots);
  ASSERT_EQ(shadowed_spot_lights(w.scene).size(), 4u);
  EXPECT_TRUE(unshadowed_casters(w.scene).empty());
  const FrameCamera cam = w.camera("overview");
  const auto hits = primary_hits(w.rays, cam, kW, kH);
  std::size_t compared_dark = 0;
  for (const ShadowSettings& s : {ShadowSettings{.method = ShadowMethod::Hard, .map_size = 2048},
                                  ShadowSettings{.method = ShadowMethod::Pcf, .map_size = 2048}}) {
    const int r = s.method == ShadowMethod::Hard ? 0 : s.kernel / 2;
    for (int k = 0; k < 4; ++k) {
      const Light& spot = w.scene.lights[std::size_t(shadowed_spot_lights(w.scene)[std::size_t(k)])];
      const ImageF truth = spot_shadow_truth(w.rays, cam, kW, kH, spot);
      std::size_t masked = 0, dark = 0;
      for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
          if (truth.at(x, y, 2) > 0.5f) ++masked, dark += truth.at(x, y, 0) < 0.5f;
      const ImageF v = w.spot_visibility(cam, s, k);
      ASSERT_TRUE(w.stage.spots_mapped()[std::size_t(k)]);
      const AtlasTile tile = w.stage.spot_tile(k);
      ASSERT_EQ(tile.size, 1024);
      int widest = 0;
      auto band = spot_band(hits, truth, spot, w.stage.spot_frustums()[std::size_t(k)], tile.size, cam, s, r, &widest);
      exclude_raster_mask(v, band);
      // The band on the receiver (light_edge_band.h [receiver-probe]), probed only where the map
      // and the truth differ outside the image's band.
      const std::size_t excused =
          probe_receivers(w.rays, hits, truth, v, spot, s, r, kW, kH,
                          [&](float d) { return w.stage.spot_frustums()[std::size_t(k)].texel_world(d, tile.size); }, band)
              .excused;
      const VisibilityError e = visibility_error(v, truth, 0, &band);
      std::size_t shadowed_compared = 0;
      for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
          shadowed_compared += truth.at(x, y, 2) > 0.5f && truth.at(x, y, 0) < 0.5f && !band[std::size_t(y) * kW + x];
      compared_dark += shadowed_compared;
      std::printf("%s, %s (tile at %d, %d): %zu pixels in its cone, %zu shadowed; band up to %d px; compared %zu (%zu "
                  "in shadow), wrong %.4f%%, mean |error| %.5f; the probe on the receiver excused %zu\n",
                  kMethodNames[int(s.method)].c_str(), spot.name.c_str(), tile.x, tile.y, masked, dark, widest, e.pixels,
                  shadowed_compared, 100 * e.wrong, e.mean_abs, excused);
      ASSERT_GT(masked, std::size_t(kW * kH / 40)) << spot.name;
      ASSERT_GT(dark, masked / 20) << spot.name;  // the columns' shadows are there to get right
      // The band leaves a good part of each cone to compare (grazing receivers, with their slope
      // bias, and the columns' narrow shadows take the rest), and some of it in shadow.
      ASSERT_GT(e.pixels, masked / 8) << spot.name;
      ASSERT_GT(shadowed_compared, std::size_t(20)) << spot.name;
      EXPECT_EQ(e.wrong, 0.0) << kMethodNames[int(s.method)] << ", " << spot.name;
      // Nor is any tap of PCF's wrong there: each compares with the receiver's plane, so the
      // error is exactly 0 (as the cube maps', test_06_point_shadows_gl.cpp [point-gl]).
      EXPECT_EQ(e.mean_abs, 0.0) << kMethodNames[int(s.method)] << ", " << spot.name;
    }
  }
  EXPECT_GT(compared_dark, std::size_t(400));
}
// [/atlas-gl]

// [atlas-bleed-gl]
// Bleeding between tiles. Three spots, so a 2 x 2 grid: spot A in tile 0 (the atlas's lower
// left) shines straight down on the floor; its right neighbour (tile 1) and the one above it
// (tile 2) belong to spots B and C, which hold either the floor 10 cm below them (depths near
// their near plane: a shadow to any receiver that compares with them) or nothing (B and C above
// the scene looking up: the far plane, lit). A PCF 15x15 kernel on a 256^2 atlas (128^2 tiles)
// reaches 7 texels past the tile's edge from A's receivers at the rim of its cone. A's visibility
// must be the same, bit for bit, whatever B and C hold; and the test holds something only if
// enough of A's receivers have taps that cross into B's or C's tile (counted on the CPU from A's
// frustum).
TEST(SpotAtlasGl, PcfTapsNeverReadTheNeighbouringTile) {
  const Light a = marked_spot("spot_a", {0.f, 3.f, 0.f}, {0.f, -1.f, 0.f}, 0.8f);
  auto neighbours = [&](bool blind) {
    if (blind)
      return std::vector<Light>{a, marked_spot("spot_b", {0.f, 0.1f, -9.f}, {0.f, -1.f, 0.f}, 0.8f),
                                marked_spot("spot_c", {0.f, 0.1f, 9.f}, {0.f, -1.f, 0.f}, 0.8f)};
    return std::vector<Light>{a, marked_spot("spot_b", {0.f, 80.f, -9.f}, {0.f, 1.f, 0.f}, 0.8f),
                              marked_spot("spot_c", {0.f, 80.f, 9.f}, {0.f, 1.f, 0.f}, 0.8f)};
  };
  Atrium blind(neighbours(true)), empty(neighbours(false));
  const ShadowSettings s{.method = ShadowMethod::Pcf, .map_size = 256, .kernel = 15};
  const int r = s.kernel / 2;
  const FrameCamera cam = looking_down({0.f, 9.f, 0.f});
  const ImageF v_blind = blind.spot_visibility(cam, s, 0), v_empty = empty.spot_visibility(cam, s, 0);
  ASSERT_EQ(blind.stage.spot_tile(0).x, 0);
  ASSERT_EQ(blind.stage.spot_tile(1).x, 128);
  ASSERT_EQ(blind.stage.spot_tile(2).y, 128);
  ASSERT_TRUE(blind.stage.spots_mapped()[1] && blind.stage.spots_mapped()[2]);
  // A's receivers whose taps reach past its tile's right or top edge (into tile 1 or 2).
  const auto hits = primary_hits(blind.rays, cam, kW, kH);
  const glm::mat4 m = blind.stage.spot_frustums()[0].view_projection();
  std::size_t crossing = 0, lit = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const auto& h = hits[std::size_t(y) * kW + std::size_t(x)];
      if (!h || (v_empty.at(x, y, 2) > 0.3f && v_empty.at(x, y, 0) < 0.2f)) continue;  // blue: outside A's cone
      lit += v_empty.at(x, y, 0) > 0.5f;
      const glm::vec4 clip = m * glm::vec4(h->position, 1.f);
      const glm::vec2 uv = glm::vec2(clip) / clip.w * 0.5f + 0.5f;
      crossing += std::max(uv.x, uv.y) > 1.f - float(r) / 128.f;
    }
  std::size_t differ = 0;
  for (std::size_t i = 0; i < v_blind.data.size(); ++i) differ += v_blind.data[i] != v_empty.data[i];
  std::printf("spot A: %zu lit pixels, %zu whose taps cross into tile 1 or 2; %zu values differ\n", lit, crossing, differ);
  ASSERT_GT(crossing, std::size_t(100));
  ASSERT_GT(lit, std::size_t(1000));
  EXPECT_EQ(differ, 0u);
}
// [/atlas-bleed-gl]
