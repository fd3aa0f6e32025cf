// Chapter 06's hard cases of the receiver's normal, on the GPU (llvmpipe in CI), against the
// ray-traced truth (shadow_truth.h): small scenes built here, a bumpy normal-mapped floor under
// a sun, where the biases and PCF's receiver plane must follow the surface's geometry and not
// the normal map's bumps (shaders/geometric_normal.glsl). Three cases: (a) the floor alone at a
// grazing sun (acne where a bump tilts towards the sun, holes where it tilts away), (b) a 2 cm
// wall standing on it (the lookup must not be pushed through the wall: light behind it), (c) a
// thin rail just above it (the bias must not lift the rail's shadow off the floor).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/06_shadows/shadow_metrics.h"
#include "chapters/06_shadows/shadow_stage.h"
#include "chapters/06_shadows/shadow_truth.h"
#include "common/target.h"
#include "tests/unit/gl_environment.h"

using namespace lp;
using namespace lp::ch06;

namespace {

constexpr int kW = 320, kH = 180;

// [hard-case-scene]
// A box of flat faces, each its own four vertices (normal, tangent along the face's u, uv in
// units of `uv_metres` of world space, so a normal map tiles at that size), wound to face out.
void add_box(Scene& s, int material, glm::vec3 lo, glm::vec3 hi, float uv_metres) {
  const auto first_index = static_cast<std::uint32_t>(s.indices.size());
  const glm::vec3 mid = 0.5f * (lo + hi), half = 0.5f * (hi - lo);
  for (int axis = 0; axis < 3; ++axis)
    for (float sign : {-1.f, 1.f}) {
      glm::vec3 n(0);
      n[axis] = sign;
      glm::vec3 u(0);
      u[(axis + 1) % 3] = 1.f;
      const glm::vec3 v = glm::cross(n, u);  // u x v = n: counter-clockwise seen from outside
      const auto first_vertex = static_cast<std::uint32_t>(s.vertices.size());
      for (glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
        const glm::vec3 p = mid + n * half + (u * c.x + v * c.y) * half;
        s.vertices.push_back(Vertex{p, n, glm::vec2(glm::dot(p, u), glm::dot(p, v)) / uv_metres, glm::vec4(u, 1)});
      }
      for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) s.indices.push_back(first_vertex + i);
    }
  s.meshes.push_back(Mesh{"box", {Primitive{first_index, 36, material}}});
  s.instances.push_back(Instance{"box " + std::to_string(s.instances.size()), int(s.meshes.size()) - 1, glm::mat4(1), {}});
  s.bounds_min = s.instances.size() == 1 ? lo : glm::min(s.bounds_min, lo);
  s.bounds_max = s.instances.size() == 1 ? hi : glm::max(s.bounds_max, hi);
}

// A normal map of round bumps: the height a sin(2 pi x) sin(2 pi y) over one tile, its steepest
// slope kBumpTilt; every direction of tilt up to that occurs on each tile.
constexpr float kBumpTilt = 0.6981f;  // radians (40 degrees)
Texture bump_map() {
  constexpr int n = 64;
  Texture t{"bumps (test)", ImageRGBA8::blank(n, n), false, false};
  const float k = std::tan(kBumpTilt);  // the largest slope, where one sine is 1 and the other's derivative peaks
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float u = 6.2831853f * (float(x) + 0.5f) / n, v = 6.2831853f * (float(y) + 0.5f) / n;
      const glm::vec3 m = glm::normalize(glm::vec3(-k * std::cos(u) * std::sin(v), -k * std::sin(u) * std::cos(v), 1.f));
      std::uint8_t* p = t.image.at(x, y);
      for (int c = 0; c < 3; ++c) p[c] = std::uint8_t(std::lround((m[c] * 0.5f + 0.5f) * 255.f));
      p[3] = 255;
    }
  return t;
}

// A 20 m square of bumpy floor (the atrium's size, so that a 1024 map over the whole of it has
// texels of its size: cm, about a thin caster's thickness), the sun at `elevation` over it from
// -x (shining towards +x), and a grey material for the casters the cases add.
Scene bumpy_floor(float elevation_degrees) {
  Scene s;
  s.path = "bumpy floor (test)";
  s.textures.push_back(bump_map());
  s.materials.push_back(Material{.name = "bumpy floor", .base_color = glm::vec4(0.6f, 0.6f, 0.6f, 1), .normal_texture = 0});
  s.materials.push_back(Material{.name = "caster", .base_color = glm::vec4(0.5f, 0.5f, 0.5f, 1)});
  add_box(s, 0, {-10.f, -0.2f, -10.f}, {10.f, 0.f, 10.f}, 0.25f);
  const float e = glm::radians(elevation_degrees);
  Light sun;
  sun.name = "sun";
  sun.type = LightType::Directional;
  sun.intensity = 3.f;
  sun.direction = glm::normalize(glm::vec3(std::cos(e), -std::sin(e), 0.15f));
  s.lights.push_back(sun);
  s.ambient = glm::vec3(0.05f);
  return s;
}
// [/hard-case-scene]

FrameCamera look(glm::vec3 eye, glm::vec3 target, glm::vec3 up = {0, 1, 0}) {
  Camera c;
  c.world = glm::inverse(glm::lookAt(eye, target, up));
  c.yfov = 0.7f, c.znear = 0.05f, c.zfar = 60.f;
  return frame_camera(c, float(kW) / kH);
}

struct World {
  explicit World(Scene s) : scene(std::move(s)), gpu(scene), rays(scene), frame(gpu), stage(gpu, find_sun(scene)) {
    frame.volumes().set_lights(ch03::build_light_set(
        scene.lights, ch03::cut_threshold(1.f, ch03::peak_reflectance(scene)), frame.volumes().shapes()));
    frame.add_stage(stage);
  }
  ImageF visibility(const FrameCamera& cam, const ShadowSettings& s) {
    ColourTarget target(kW, kH, GL_RGBA32F);
    stage.set(s, ShadowPicture::Visibility);
    frame.render(cam, {target.framebuffer(), kW, kH});
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    return target.read();
  }
  ImageF truth(const FrameCamera& cam) { return cached_shadow_truth(scene, rays, cam, kW, kH, find_sun(scene).direction); }
  Scene scene;
  SceneGpu gpu;
  RayScene rays;
  ch03::DeferredFrame frame;
  ShadowStage stage;
};

// The map over the whole floor (not cut to the view): texels of the atrium's size.
ShadowSettings whole_floor(ShadowMethod m) { return {.method = m, .map_size = 1024, .fit_to_view = false}; }

// [hard-case-band]
// Where a shadow edge may lie on screen: around each lit/shadowed boundary of the hard truth,
// as far as the map moves an edge sideways for that pixel's receiver, in the receiver's
// geometry: the nearest texel (half a texel), the normal offset (sin theta texels) and PCF's
// radius, in the light's plane, on the receiver stretched by 1 / cos theta (the sun's slant),
// over the pixel's footprint. The depth biases move no edge sideways: they only light what lies
// within them along the light, which is what these cases look for. Pixels next to the mask's
// border (one pixel: the centre ray and the raster may see different surfaces there) are out.
std::vector<bool> edge_band(const RayScene& rays, const FrameCamera& cam, const ImageF& truth, glm::vec3 to_sun,
                            float texel, const ShadowSettings& s) {
  const auto hits = primary_hits(rays, cam, kW, kH);
  const int r = s.method == ShadowMethod::Hard ? 0 : s.kernel / 2;
  std::vector<bool> band(std::size_t(kW) * kH, false);
  auto at = [&](int x, int y) { return std::size_t(y) * kW + std::size_t(x); };
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      if (truth.at(x, y, 2) < 0.5f) continue;
      const Hit& h = *hits[at(x, y)];
      const float c = std::clamp(std::abs(glm::dot(to_sun, h.geometric_normal)), 1e-4f, 1.f);
      const float s_theta = std::sqrt(1.f - c * c);
      const float metres = (0.5f + s.normal_offset * s_theta + float(r)) * texel / c;
      const float footprint = h.t * 2.f * std::tan(cam.yfov / 2.f) / float(kH);
      const int reach = int(std::ceil(metres / footprint));
      for (int dy = -reach; dy <= reach && !band[at(x, y)]; ++dy)
        for (int dx = -reach; dx <= reach; ++dx) {
          const int u = x + dx, v = y + dy;
          if (u < 0 || v < 0 || u >= kW || v >= kH) continue;
          const bool border = std::max(std::abs(dx), std::abs(dy)) <= 1 && truth.at(u, v, 2) < 0.5f;
          const bool edge = truth.at(u, v, 2) > 0.5f && (truth.at(u, v, 0) > 0.5f) != (truth.at(x, y, 0) > 0.5f);
          if (border || edge) {
            band[at(x, y)] = true;
            break;
          }
        }
    }
  return band;
}
// [/hard-case-band]

// Pixels compared: in the truth's mask, outside the band and where the method's picture saw a
// surface facing the sun (outside_method_mask: its fragment and the centre ray may differ).
struct Sides {
  std::size_t lit = 0, dark = 0;        // the truth's, compared
  std::size_t acne = 0;   // truly lit, read darker by half a tap of the kernel or more (one tap shadowed)
  std::size_t holes = 0;  // truly shadowed, read lit (above 0.5)
};
Sides compare(const ImageF& v, const ImageF& truth, const std::vector<bool>& band, const ShadowSettings& settings) {
  const int k = settings.method == ShadowMethod::Hard ? 1 : settings.kernel;
  const float half_tap = 0.5f / float(k * k);
  const std::vector<bool> outside = outside_method_mask(v);
  Sides s;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const std::size_t i = std::size_t(y) * kW + std::size_t(x);
      if (truth.at(x, y, 2) < 0.5f || band[i] || outside[i]) continue;
      if (truth.at(x, y, 0) > 0.5f) ++s.lit, s.acne += v.at(x, y, 0) < 1.f - half_tap;
      else ++s.dark, s.holes += v.at(x, y, 0) > 0.5f;
    }
  return s;
}

}  // namespace

namespace {
// A case as a picture (for the book, where LIGHTPASS_HARD_CASE_PICTURES names a folder): the
// truth lit light grey, shadowed dark grey, outside its mask black; acne red, holes green.
void save_case(const char* name, const ImageF& v, const ImageF& truth, const std::vector<bool>& band,
               const ShadowSettings& settings) {
  const int k = settings.method == ShadowMethod::Hard ? 1 : settings.kernel;
  const float half_tap = 0.5f / float(k * k);  // as compare(): one tap shadowed is acne
  if (!std::getenv("LIGHTPASS_HARD_CASE_PICTURES")) return;
  ImageF d = ImageF::blank(kW, kH, 3);
  const std::vector<bool> outside = outside_method_mask(v);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const std::size_t i = std::size_t(y) * kW + std::size_t(x);
      const bool in = truth.at(x, y, 2) > 0.5f && !outside[i];
      const float tv = truth.at(x, y, 0), mv = v.at(x, y, 0);
      const float base = !in ? 0.05f : tv > 0.5f ? 0.8f : 0.25f;
      glm::vec3 c(base);
      if (in && !band[i] && tv > 0.5f && mv < 1.f - half_tap) c = {1, 0, 0};
      if (in && !band[i] && tv < 0.5f && mv > 0.5f) c = {0, 1, 0};
      for (int k = 0; k < 3; ++k) d.at(x, y, k) = c[k];
    }
  save_png(std::string(std::getenv("LIGHTPASS_HARD_CASE_PICTURES")) + "/" + name + ".png", to_srgb8(d));
}

struct Case {
  World world;
  FrameCamera camera;
  ImageF truth;
  Case(Scene s, FrameCamera cam) : world(std::move(s)), camera(cam), truth(world.truth(cam)) {}
  // The method's sides against the truth outside the band, and its light leaks there.
  std::pair<Sides, LightLeak> run(const ShadowSettings& s, const char* picture) {
    const ImageF v = world.visibility(camera, s);
    const float texel = world.stage.frustum().texel_world(s.map_size);
    const auto band = edge_band(world.rays, camera, truth, -find_sun(world.scene).direction, texel, s);
    std::vector<bool> exclude = outside_method_mask(v);
    for (std::size_t i = 0; i < exclude.size(); ++i) exclude[i] = exclude[i] || band[i];
    const Sides sides = compare(v, truth, band, s);
    const LightLeak leak = light_leak(v, truth, &exclude);
    std::printf("%s (%s, %.2f cm texels): %zu lit compared, %zu acne; %zu dark, %zu holes; leaks %zu of %zu\n", picture,
                kMethodNames[int(s.method)].c_str(), 100 * texel, sides.lit, sides.acne, sides.dark, sides.holes,
                leak.leaking, leak.full_shadow);
    save_case(picture, v, truth, band, s);
    return {sides, leak};
  }
};
}  // namespace

// [hard-case-a]
// (a) A normal-mapped receiver at a grazing sun: the bumpy floor with the sun 10 degrees over
// it and a 1 m block casting. The shading normal of a bump tilted 30 degrees towards the sun
// says the floor faces it at 40 degrees: its slope bias is a seventh of the 80 degrees' and
// PCF's receiver plane tilts the wrong way, so the floor shadows itself (acne); a bump tilted
// away asks for ten times the bias, which lights the block's shadow (holes). With the geometric
// normal every pixel of the floor is biased for the plane it lies on. Allowed outside the band:
// none, hard and PCF 3x3.
TEST(HardCasesGl, BumpyFloorAtAGrazingSunHasNoAcneAndNoHoles) {
  Scene s = bumpy_floor(10.f);
  add_box(s, 1, {-2.f, 0.f, -0.5f}, {-1.f, 1.f, 0.5f}, 1.f);
  Case c(std::move(s), look({1.5f, 3.5f, 2.f}, {1.5f, 0.f, -0.2f}));
  for (ShadowMethod m : {ShadowMethod::Hard, ShadowMethod::Pcf}) {
    ShadowSettings st = whole_floor(m);
    st.kernel = 5;
    const auto [sides, leak] = c.run(st, m == ShadowMethod::Hard ? "06_hard_case_bumps_hard" : "06_hard_case_bumps_pcf");
    ASSERT_GT(sides.lit, std::size_t(5000));  // the bumps in the sun and in the block's shadow,
    ASSERT_GT(sides.dark, std::size_t(1000)); // well outside the band
    EXPECT_EQ(sides.acne, 0u) << kMethodNames[int(m)];
    EXPECT_EQ(sides.holes, 0u) << kMethodNames[int(m)];
  }
}
// [/hard-case-a]

// [hard-case-b]
// (b) A thin caster: a wall 2 cm thick, 1 m high, on the bumpy floor, the sun 10 degrees up
// behind it. The slope-scaled bias a receiver at 80 degrees needs (tan 80 = 5.7 texels of
// 2.3 cm, 13 cm along the light) is longer than the wall is thick: the floor behind the wall
// reads past the wall and is lit along its foot, a leak the derived reach predicts (a strip
// where (distance behind + thickness) / cos(elevation) is below the bias). The normal offset
// moves the lookup along the floor's geometric normal, up, parallel to the wall: with it in
// place of the slope bias nothing leaks, and the grazing floor still has no acne (the offset's
// sin(theta) is the slope's share). Allowed with the offset: no leak and no acne outside the band.
TEST(HardCasesGl, ThinWallLeaksUnderTheSlopeBiasButNotUnderTheNormalOffset) {
  Scene s = bumpy_floor(10.f);
  add_box(s, 1, {0.f, 0.f, -1.5f}, {0.02f, 1.f, 1.5f}, 1.f);
  Case c(std::move(s), look({1.2f, 1.4f, 2.2f}, {0.2f, 0.f, 1.1f}));
  ShadowSettings slope = whole_floor(ShadowMethod::Hard);
  const auto [slope_sides, slope_leak] = c.run(slope, "06_hard_case_wall_slope");
  ShadowSettings offset = slope;
  offset.slope_bias = 0.f;
  offset.normal_offset = 2.f;
  const auto [sides, leak] = c.run(offset, "06_hard_case_wall_offset");
  ASSERT_GT(leak.full_shadow, std::size_t(5000));
  EXPECT_GT(slope_leak.leaking, std::size_t(50));  // the hard case is there: the slope bias leaks
  EXPECT_EQ(leak.leaking, 0u);
  EXPECT_EQ(sides.acne, 0u);
}
// [/hard-case-b]

// [hard-case-c]
// (c) A thin occluder near the receiver: a rail 3 cm square, its underside 5 cm over the bumpy
// floor, the sun 30 degrees up across it; a 2048 map (1.2 cm texels), so that its shadow, 8 cm
// wide, is wider than the band. The lookup reaches past the rail when the bias along the
// light, (constant + slope tan theta) texels, plus the normal offset's rise over sin(elevation),
// exceeds the gap along the light, 5 cm / sin 30 = 10 cm: with the geometric normal it is 4 cm;
// a bump tilted away from the sun asks for up to 10.5 texels, 12 cm, and lifts the shadow off the
// floor where it should be (peter-panning). Allowed outside the band: no holes, no acne.
TEST(HardCasesGl, ThinRailKeepsItsShadowOnTheFloor) {
  Scene s = bumpy_floor(30.f);
  add_box(s, 1, {-0.015f, 0.03f, -1.f}, {0.015f, 0.06f, 1.f}, 1.f);
  Case c(std::move(s), look({0.08f, 0.5f, 0.f}, {0.08f, 0.f, 0.f}, {1, 0, 0}));
  ShadowSettings hard = whole_floor(ShadowMethod::Hard);
  hard.map_size = 2048;
  const auto [sides, leak] = c.run(hard, "06_hard_case_rail");
  ASSERT_GT(sides.dark, std::size_t(1000));  // the rail's shadow, outside the band
  EXPECT_EQ(sides.holes, 0u);
  EXPECT_EQ(sides.acne, 0u);
}
// [/hard-case-c]

// [hard-case-d]
// (d) A caster's silhouette over a far floor: a bar floating 0.6 to 0.8 m over the bumpy floor,
// across the view, seen from 6 m up, the sun 30 degrees up ahead of the camera (the bar's shadow
// falls nearer the camera, below the view). The floor seen just past the bar's top edge has, along the image's
// column, one neighbour on the floor and one on the bar, 0.9 m nearer: geometric_normal.glsl's
// surface_step must take the floor's. The step to the bar runs along the view ray, and a normal
// built on it leans away from the camera by the view's depression (about 64 degrees), towards
// this sun: PCF's receiver plane then slopes a tenth as steeply as the floor does across the
// kernel, and the outer taps on one side shadow the floor (acne along the whole silhouette). The
// view is taken twice, the second rolled half a turn, so that the bar lies on the pixel grid's
// other side of those pixels (behind them, then ahead). Choosing by the flatter step to the
// shading normal failed here at 2 % of those pixels, where a bump tilts the normal map towards
// the view ray; the choice by the depth's second difference does not. Allowed outside the band:
// no acne, no holes; and the floor pixels beside the silhouette must be among those compared.
namespace {
// Pixels on the floor whose neighbour in the column is on the bar, at least half a metre nearer.
std::vector<bool> beside_silhouette(const RayScene& rays, const FrameCamera& cam, int floor_instance) {
  const auto hits = primary_hits(rays, cam, kW, kH);
  std::vector<bool> beside(std::size_t(kW) * kH, false);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const auto& h = hits[std::size_t(y) * kW + std::size_t(x)];
      if (!h || h->instance != floor_instance) continue;
      for (int v : {y - 1, y + 1}) {
        if (v < 0 || v >= kH) continue;
        const auto& n = hits[std::size_t(v) * kW + std::size_t(x)];
        if (n && n->instance != floor_instance && n->t < h->t - 0.5f) beside[std::size_t(y) * kW + std::size_t(x)] = true;
      }
    }
  return beside;
}
}  // namespace

TEST(HardCasesGl, FloorBesideACastersSilhouetteKeepsItsOwnPlane) {
  for (glm::vec3 up : {glm::vec3(0, 1, 0), glm::vec3(0, -1, 0)}) {
    Scene s = bumpy_floor(30.f);
    add_box(s, 1, {1.5f, 0.6f, -4.f}, {1.7f, 0.8f, 4.f}, 1.f);
    Case c(std::move(s), look({4.f, 6.f, 0.f}, {-1.f, 0.f, 0.f}, up));
    const std::vector<bool> beside = beside_silhouette(c.world.rays, c.camera, 0);
    for (ShadowMethod m : {ShadowMethod::Hard, ShadowMethod::Pcf}) {
      ShadowSettings st = whole_floor(m);
      st.kernel = 5;
      const ImageF v = c.world.visibility(c.camera, st);
      const auto [sides, leak] = c.run(st, up.y > 0 ? (m == ShadowMethod::Hard ? "06_hard_case_silhouette_hard" : "06_hard_case_silhouette_pcf")
                                                      : (m == ShadowMethod::Hard ? "06_hard_case_silhouette_rolled_hard"
                                                                                 : "06_hard_case_silhouette_rolled_pcf"));
      // The silhouette's floor pixels on their own: compared where compare() would.
      const float texel = c.world.stage.frustum().texel_world(st.map_size);
      const auto band = edge_band(c.world.rays, c.camera, c.truth, -find_sun(c.world.scene).direction, texel, st);
      std::vector<bool> only_beside = band;
      for (std::size_t i = 0; i < only_beside.size(); ++i) only_beside[i] = band[i] || !beside[i];
      const Sides at_silhouette = compare(v, c.truth, only_beside, st);
      std::printf("  beside the silhouette: %zu lit compared, %zu acne; %zu dark, %zu holes\n", at_silhouette.lit,
                  at_silhouette.acne, at_silhouette.dark, at_silhouette.holes);
      ASSERT_GT(at_silhouette.lit, std::size_t(200)) << kMethodNames[int(m)];  // a row of the floor beside the bar
      EXPECT_EQ(at_silhouette.acne, 0u) << kMethodNames[int(m)] << (up.y > 0 ? "" : ", rolled");
      EXPECT_EQ(sides.acne, 0u) << kMethodNames[int(m)] << (up.y > 0 ? "" : ", rolled");
      EXPECT_EQ(sides.holes, 0u) << kMethodNames[int(m)] << (up.y > 0 ? "" : ", rolled");
    }
  }
}
// [/hard-case-d]
