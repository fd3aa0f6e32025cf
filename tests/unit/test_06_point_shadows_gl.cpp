// Chapter 06's point lights on the GPU (llvmpipe in CI): each light's cube map (cube_math.h,
// shadow_visibility.glsl [point-glsl]) read back as its visibility alone, against one ray per
// pixel toward the light (spot_shadow_truth, which takes a point light too), on the atrium with
// every point light casting (ShadowSettings::all_point_lights; the scene marks none).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/06_shadows/cube_math.h"
#include "chapters/06_shadows/shadow_stage.h"
#include "chapters/06_shadows/shadow_truth.h"
#include "common/paths.h"
#include "common/target.h"
#include "tests/unit/gl_environment.h"
#include "tests/unit/light_edge_band.h"

using namespace lp;
using namespace lp::ch06;

namespace {

constexpr int kW = 320, kH = 180;

struct Atrium {
  explicit Atrium(void (*edit)(Scene&) = nullptr)
      : scene(load(edit)), gpu(scene), rays(scene), frame(gpu), stage(gpu, find_sun(scene)) {
    frame.volumes().set_lights(ch03::build_light_set(
        scene.lights, ch03::cut_threshold(1.f, ch03::peak_reflectance(scene)), frame.volumes().shapes()));
    frame.add_stage(stage);
  }
  static Scene load(void (*edit)(Scene&)) {
    Scene s = load_scene(from_root("assets/atrium/atrium.gltf"));
    if (edit) edit(s);
    return s;
  }
  FrameCamera camera(const std::string& view) const { return frame_camera(scene.camera(view), float(kW) / kH); }
  // Point light k's visibility alone (ShadowPicture::PointVisibility), top row first.
  ImageF point_visibility(const FrameCamera& cam, ShadowSettings s, int k) {
    ColourTarget target(kW, kH, GL_RGBA32F);
    s.point_shown = k;
    stage.set(s, ShadowPicture::PointVisibility);
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

std::unique_ptr<Atrium> atrium;

class PointShadowsGl : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { atrium = std::make_unique<Atrium>(); }
  static void TearDownTestSuite() { atrium.reset(); }
};

// Pixels the rasteriser marks as sky or facing away (blue) where the truth's mask says
// otherwise: the pixel's centre ray and the fragment saw different surfaces (a silhouette).
void exclude_raster_mask(const ImageF& v, std::vector<bool>& exclude) {
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      if (v.at(x, y, 2) > 0.3f && v.at(x, y, 0) < 0.2f) exclude[std::size_t(y) * kW + x] = true;
}

// [point-band]
// The pixels near a shadow edge of the truth, each by its own reach: a receiver at distance d
// from the light, at angle theta to it, seen t metres from the eye, may see the map's edge moved
// by `texels` (half a texel, the biases with this receiver's tan(theta) capped at kMaxSlope as
// the hook caps it, the normal offset, PCF's r) of w(d) = 2 d / N each: over the pixel's
// footprint t 2 tan(fov / 2) / H (a surface seen square; slanted, fewer pixels), that many
// pixels. A pixel is in the band when within its own count of pixels lies a lit/shadowed
// boundary of the truth, the border of what the light reaches, a crease (neighbours on
// surfaces whose geometric normals differ: a texel holds one depth, the nearer surface's), or
// the image's border (an edge just outside the image is not seen). Returns the band and its
// widest reach.
std::vector<bool> point_band(const std::vector<std::optional<Hit>>& hits, const ImageF& truth, const Light& l,
                             const FrameCamera& cam, const ShadowSettings& s, int r, int* widest) {
  return light_edge_band(hits, truth, l, cam, s, r, kW, kH,
                          [&](float d) { return cube_texel_world(d, s.cube_size); }, widest);
}
// [/point-band]

}  // namespace

// [point-gl]
// Every point light of the atrium from its cube map (1024 texels a face), against its
// ray-traced hard shadows, from the overview, outside the band above. Allowed there, hard and PCF
// 3x3: no pixel on the wrong side.
TEST_F(PointShadowsGl, CubeMapsMatchTheRayTracedShadowsOutsideTheBand) {
  const FrameCamera cam = atrium->camera("overview");
  const auto hits = primary_hits(atrium->rays, cam, kW, kH);
  const std::vector<int> lights = shadowed_point_lights(atrium->scene, true);
  ASSERT_EQ(lights.size(), 8u);
  std::size_t compared_dark = 0;
  for (const ShadowSettings& s : {ShadowSettings{.method = ShadowMethod::Hard, .all_point_lights = true, .cube_size = 1024},
                                  ShadowSettings{.method = ShadowMethod::Pcf, .all_point_lights = true, .cube_size = 1024}}) {
    const int r = s.method == ShadowMethod::Hard ? 0 : s.kernel / 2;
    for (int k = 0; k < int(lights.size()); ++k) {
      const Light& l = atrium->scene.lights[std::size_t(lights[std::size_t(k)])];
      const ImageF truth = spot_shadow_truth(atrium->rays, cam, kW, kH, l);
      const ImageF v = atrium->point_visibility(cam, s, k);
      ASSERT_TRUE(atrium->stage.points_mapped()[std::size_t(k)]);
      int widest = 0;
      auto band = point_band(hits, truth, l, cam, s, r, &widest);
      exclude_raster_mask(v, band);
      // The band on the receiver (light_edge_band.h [receiver-probe], probe_receivers).
      const auto [probed, excused] = probe_receivers(atrium->rays, hits, truth, v, l, s, r, kW, kH,
                                                     [&](float d) { return cube_texel_world(d, s.cube_size); }, band);
      const VisibilityError e = visibility_error(v, truth, 0, &band);
      std::size_t reached = 0, dark = 0;
      for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
          reached += truth.at(x, y, 2) > 0.5f;
          dark += truth.at(x, y, 2) > 0.5f && truth.at(x, y, 0) < 0.5f && !band[std::size_t(y) * kW + x];
        }
      compared_dark += dark;
      std::printf("%s, %s: %zu pixels reached; band up to %d px; compared %zu (%zu shadowed), wrong %.4f%%, "
                  "mean |error| %.5f; %zu differing pixels probed on the receiver, %zu of them beside a boundary there\n",
                  kMethodNames[int(s.method)].c_str(), l.name.c_str(), reached, widest, e.pixels, dark, 100 * e.wrong,
                  e.mean_abs, probed, excused);
      // The band leaves a good part of what the light reaches to compare (grazing receivers,
      // with their slope bias, and the borders of what it reaches take the rest).
      ASSERT_GT(e.pixels, reached / 4) << l.name;
      EXPECT_EQ(e.wrong, 0.0) << kMethodNames[int(s.method)] << ", " << l.name;
      // Nor is any tap of PCF's wrong: each compares with the receiver's plane, the geometric one
      // (geometric_normal.glsl), which the floor's normal map does not tilt at the tiles' grooves
      // (with the shading normal a tap or two of nine shadowed them there). Outside the band every
      // tap is then right, and the error is exactly 0. (Before the probe on the receiver, two
      // pixels of the end wall 30 m away, for nave_rose and nave_violet, read two or three taps of
      // nine lit in the truth's shadow: their taps, 3.6 cm apart, reach a lit gap 4 cm wide between
      // two casters' shadows that the truth's pixels, 16 cm apart there, step over.)
      EXPECT_EQ(e.mean_abs, 0.0) << kMethodNames[int(s.method)] << ", " << l.name;
      // The probe excuses a few pixels, not the map's errors wholesale.
      EXPECT_LE(excused, std::size_t(10)) << kMethodNames[int(s.method)] << ", " << l.name;
    }
  }
  EXPECT_GT(compared_dark, std::size_t(2000));  // the columns' shadows are there to get right
}
// [/point-gl]

// [point-seams-gl]
// The faces' seams: pixels whose neighbour (right or below) lies on another face of the light's
// cube (cube_face_coords of the directions from the light), both outside the band, compared with
// the truth on each side. A face drawn with less than its 90 degrees leaves its outer texels at
// the cleared far depth, lit; PCF's taps past a face's edge must read the next face. The atrium
// with one light marked to cast, 45 degrees from column l3 across the floor (the faces -X and -Z
// meet on that diagonal), so the column's shadow lies along the seam. Allowed: none on the wrong
// side; and the seam must cross the shadow, or the test would hold nothing.
namespace {
void add_diagonal_light(Scene& s) {
  Light l;
  l.name = "test_diagonal";
  l.type = LightType::Point;
  l.intensity = 5.f;
  l.position = {-1.f, 2.f, 3.f};  // column l3 stands at (-4, 0): 3 m along -x and 3 m along -z
  l.casts_shadows = true;
  s.lights.push_back(l);
}
}  // namespace

TEST(PointShadowsGlSeams, NoLightLeaksAcrossTheCubeFacesSeams) {
  Atrium w(add_diagonal_light);
  Atrium* atrium = &w;
  const FrameCamera cam = atrium->camera("overview");
  const auto hits = primary_hits(atrium->rays, cam, kW, kH);
  const std::vector<int> lights = shadowed_point_lights(atrium->scene);
  ASSERT_EQ(lights.size(), 1u);
  for (const ShadowSettings& s : {ShadowSettings{.method = ShadowMethod::Hard, .cube_size = 1024},
                                  ShadowSettings{.method = ShadowMethod::Pcf, .cube_size = 1024}}) {
    const int r = s.method == ShadowMethod::Hard ? 0 : s.kernel / 2;
    std::size_t seam = 0, seam_dark = 0, wrong = 0;
    for (int k = 0; k < int(lights.size()); ++k) {
      const Light& l = atrium->scene.lights[std::size_t(lights[std::size_t(k)])];
      const ImageF truth = spot_shadow_truth(atrium->rays, cam, kW, kH, l);
      const ImageF v = atrium->point_visibility(cam, s, k);
      int widest = 0;
      auto band = point_band(hits, truth, l, cam, s, r, &widest);
      exclude_raster_mask(v, band);
      auto usable = [&](int x, int y) {
        const std::size_t i = std::size_t(y) * kW + std::size_t(x);
        return truth.at(x, y, 2) > 0.5f && !band[i] && hits[i];
      };
      for (int y = 0; y + 1 < kH; ++y)
        for (int x = 0; x + 1 < kW; ++x) {
          if (!usable(x, y)) continue;
          const CubeFace face = cube_face_coords(hits[std::size_t(y) * kW + std::size_t(x)]->position - l.position).face;
          for (const auto& [u, w] : {std::pair{x + 1, y}, std::pair{x, y + 1}}) {
            if (!usable(u, w)) continue;
            if (cube_face_coords(hits[std::size_t(w) * kW + std::size_t(u)]->position - l.position).face == face) continue;
            for (const auto& [px, py] : {std::pair{x, y}, std::pair{u, w}}) {
              ++seam, seam_dark += truth.at(px, py, 0) < 0.5f;
              wrong += std::abs(v.at(px, py, 0) - truth.at(px, py, 0)) > 0.5f;
            }
          }
        }
    }
    std::printf("%s: %zu pixels beside a seam (%zu in shadow), %zu on the wrong side\n", kMethodNames[int(s.method)].c_str(),
                seam, seam_dark, wrong);
    ASSERT_GT(seam_dark, std::size_t(50));
    ASSERT_GT(seam - seam_dark, std::size_t(50));
    EXPECT_EQ(wrong, 0u) << kMethodNames[int(s.method)];
  }
}
// [/point-seams-gl]
