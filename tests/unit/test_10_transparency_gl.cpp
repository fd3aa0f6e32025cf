// Chapter 10's transparency on the GPU: the glass scene through chapter 03's deferred frame and
// the transparency stage, each method against the exact per-pixel order (every fragment
// captured, sorted by depth and composited on the CPU in double), and the hard cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/01_forward/ground_truth.h"
#include "chapters/02_gbuffer/layout.h"
#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/06_shadows/shadow_stage.h"
#include "chapters/10_frame/transparency.h"
#include "common/error.h"
#include "common/gl.h"
#include "common/metrics.h"
#include "common/paths.h"
#include "common/shader.h"
#include "common/target.h"
#include "tests/unit/book_data.h"
#include "tests/unit/gl_environment.h"

using namespace lp;
using namespace lp::ch10;
using lp::test::book_row;

namespace {

constexpr int kW = 320, kH = 180;

Scene glass_scene() { return load_scene(from_root("assets/glass/glass.gltf")); }

// The scene on the GPU with a deferred frame and the stage, rendering into an sRGB8 target.
struct World {
  explicit World(Scene s, const ch02::Layout& layout = ch02::our_layout())
      : scene(std::move(s)), gpu(scene), frame(gpu, layout), stage(frame, gpu), target(kW, kH) {
    frame.volumes().set_lights(ch03::build_light_set(
        scene.lights, ch03::cut_threshold(1.f, ch03::peak_reflectance(scene)), frame.volumes().shapes()));
    frame.add_stage(stage);
  }
  FrameCamera camera(const std::string& view) const { return frame_camera(scene.camera(view), float(kW) / kH); }
  ImageRGBA8 render(const FrameCamera& cam, TransparencySettings s) {
    stage.set(s);
    frame.render(cam, {target.framebuffer(), kW, kH});
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    return target.read();
  }
  ImageRGBA8 render(const std::string& view, Method m, DrawOrder order = DrawOrder::BackToFront, std::uint32_t seed = 1) {
    return render(camera(view), {.method = m, .order = order, .shuffle_seed = seed});
  }
  ExactComposite exact(const std::string& view, std::size_t per_pixel = 16) {
    render(camera(view), {.method = Method::Off});
    ExactComposite e = stage.exact_composite(frame, per_pixel);
    EXPECT_FALSE(e.overflow);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    return e;
  }
  Scene scene;
  SceneGpu gpu;
  ch03::DeferredFrame frame;
  TransparencyStage stage;
  OutputTarget target;
};

// The largest channel difference of each pixel, in 8-bit steps.
std::vector<int> steps(const ImageRGBA8& a, const ImageRGBA8& b) {
  std::vector<int> d(std::size_t(a.width) * a.height);
  for (std::size_t i = 0; i < d.size(); ++i)
    for (int c = 0; c < 3; ++c) d[i] = std::max(d[i], std::abs(int(a.pixels[i * 4 + c]) - int(b.pixels[i * 4 + c])));
  return d;
}

struct Stats {
  std::size_t pixels = 0;
  double mean = 0, p99 = 0, max = 0;
};
template <class Keep>
Stats stats(const std::vector<int>& error, Keep keep) {
  std::vector<int> e;
  for (std::size_t i = 0; i < error.size(); ++i)
    if (keep(i)) e.push_back(error[i]);
  Stats s;
  s.pixels = e.size();
  if (e.empty()) return s;
  std::sort(e.begin(), e.end());
  for (int v : e) s.mean += v;
  s.mean /= double(e.size());
  s.p99 = e[std::size_t(std::ceil(0.99 * double(e.size()))) - 1];
  s.max = e.back();
  return s;
}

Scene with_glass_alpha(float alpha, bool blend = true) {
  Scene s = glass_scene();
  for (Material& m : s.materials)
    if (m.blend) m.base_color.a = alpha, m.blend = blend;
  return s;
}

}  // namespace

// [sorted-bound]
// Sorted blending rounds into the 8-bit sRGB output after every layer (at most half a step),
// and a later layer scales the earlier rounding by (1 - alpha) in linear light, which in sRGB
// steps shrinks it too (the sRGB curve is concave: its slope at (1 - alpha) x is at most
// (1 - alpha)^-0.58 times its slope at x). The exact order is rounded once. So where the
// per-surface order is each pixel's depth order, L layers differ by at most (L + 1) / 2 steps.
int sorted_bound(int layers) { return (layers + 1) / 2; }
// [/sorted-bound]

TEST(TransparencyGl, SortedEqualsTheExactOrderWhereTheSurfacesAreInOrder) {
  World w(glass_scene());
  for (const char* view : {"front", "side", "crossing"}) {
    const ExactComposite exact = w.exact(view);
    const std::vector<int> error = steps(w.render(view, Method::Sorted), exact.image);
    std::size_t glass = 0, wrong_order = 0, over = 0, wrong_and_over = 0;
    for (std::size_t i = 0; i < error.size(); ++i) {
      if (exact.layers[i] == 0) {
        EXPECT_EQ(error[i], 0) << view << ": pixel " << i << " has no glass";
        continue;
      }
      ++glass;
      if (!exact.surface_order_right[i]) {
        ++wrong_order;
        wrong_and_over += error[i] > sorted_bound(exact.layers[i]);
      } else if (error[i] > sorted_bound(exact.layers[i])) {
        ++over;
        if (over <= 5) ADD_FAILURE() << view << ": pixel " << i % kW << "," << i / kW << ", " << exact.layers[i] << " layers, " << error[i] << " steps";
      }
    }
    EXPECT_GT(glass, 5000u) << view << ": the panes are in view";
    EXPECT_EQ(over, 0u) << view << ": pixels in order beyond (L + 1) / 2 steps";
    const Stats in_order = stats(error, [&](std::size_t i) { return exact.layers[i] > 0 && exact.surface_order_right[i]; });
    const Stats out_of_order = stats(error, [&](std::size_t i) { return exact.layers[i] > 0 && !exact.surface_order_right[i]; });
    if (std::string(view) == "crossing") {
      // The X: the pane drawn first is behind on one side of the crossing line only.
      EXPECT_GT(wrong_order, 1000u);
      EXPECT_GT(wrong_and_over, wrong_order / 4) << "sorting whole panes is visibly wrong there";
    }
    book_row("10_transparency_sorted", {{"view", view}},
             {{"glass_pixels", double(glass)}, {"wrong_order_pixels", double(wrong_order)},
              {"in_order_max", in_order.max}, {"in_order_mean", in_order.mean},
              {"wrong_order_mean", out_of_order.mean}, {"wrong_order_max", out_of_order.max}});
  }
}

TEST(TransparencyGl, WboitIsExactForOneLayerAndBoundedWhereLayersOverlap) {
  World w(glass_scene());
  for (const char* view : {"front", "side", "crossing"}) {
    const ExactComposite exact = w.exact(view);
    const std::vector<int> error = steps(w.render(view, Method::Wboit, DrawOrder::AsListed), exact.image);
    // One layer: sum w alpha c / sum w alpha is c, exactly up to the half floats' 11 bits
    // (0.05 steps at most) and the two roundings into 8 bits: at most 1 step.
    const Stats one = stats(error, [&](std::size_t i) { return exact.layers[i] == 1; });
    EXPECT_LE(one.max, 1) << view;
    EXPECT_EQ(stats(error, [&](std::size_t i) { return exact.layers[i] == 0; }).max, 0) << view;
    // Overlaps: a weighted average instead of "over". Measured on llvmpipe (book/figures/
    // 10_transparency_wboit.csv, which this test also holds): mean 3.9 to 8.3 steps, p99 7 to
    // 13, max 14 (front: the amber pane over the pink one). The bounds are about a third above
    // the worst view (mean 11, p99 18): another renderer's rounding passes, while a weight or
    // blending change that makes the average markedly worse fails.
    const Stats overlap = stats(error, [&](std::size_t i) { return exact.layers[i] >= 2; });
    EXPECT_GT(overlap.pixels, 2000u) << view;
    EXPECT_LE(overlap.mean, 11.0) << view;
    EXPECT_LE(overlap.p99, 18.0) << view;
    book_row("10_transparency_wboit", {{"view", view}},
             {{"one_layer_pixels", double(one.pixels)}, {"one_layer_max", one.max},
              {"overlap_pixels", double(overlap.pixels)}, {"overlap_mean", overlap.mean},
              {"overlap_p99", overlap.p99}, {"overlap_max", overlap.max}});
  }
}

TEST(TransparencyGl, WboitDoesNotCareAboutTheDrawOrder) {
  // Sums and products commute; in half floats they round differently in another order, by far
  // less than a step (11 bits): within one step after the rounding into 8 bits.
  World w(glass_scene());
  for (const char* view : {"front", "crossing"}) {
    const ImageRGBA8 listed = w.render(view, Method::Wboit, DrawOrder::AsListed);
    for (auto [order, seed] : {std::pair{DrawOrder::FrontToBack, 1u}, std::pair{DrawOrder::BackToFront, 1u},
                               std::pair{DrawOrder::Shuffled, 7u}, std::pair{DrawOrder::Shuffled, 11u}}) {
      const std::vector<int> d = steps(w.render(view, Method::Wboit, order, seed), listed);
      EXPECT_LE(*std::max_element(d.begin(), d.end()), 1) << view;
    }
  }
}

TEST(TransparencyGl, SortingChangesOnlyWhereLayersOverlap) {
  // Drawn front to back, "over" is wrong wherever two layers meet, and only there.
  World w(glass_scene());
  const ExactComposite exact = w.exact("front");
  const std::vector<int> d = steps(w.render("front", Method::Sorted, DrawOrder::FrontToBack),
                                   w.render("front", Method::Sorted, DrawOrder::BackToFront));
  std::size_t changed = 0;
  for (std::size_t i = 0; i < d.size(); ++i)
    if (d[i] > 0) {
      ++changed;
      EXPECT_GE(exact.layers[i], 2) << "pixel " << i << " changed with one layer or none";
    }
  EXPECT_GT(changed, 2000u);
}

TEST(TransparencyGl, GlassOfAlphaZeroChangesNoPixel) {
  World w(with_glass_alpha(0.f));
  for (const char* view : {"front", "crossing"}) {
    const ImageRGBA8 off = w.render(view, Method::Off);
    EXPECT_EQ(w.render(view, Method::Sorted).pixels, off.pixels) << view;
    EXPECT_EQ(w.render(view, Method::Wboit, DrawOrder::AsListed).pixels, off.pixels) << view;
  }
}

TEST(TransparencyGl, GlassOfAlphaOneEqualsTheOpaquePath) {
  // Alpha 1 through the stage against the same panes opaque, in the G-buffer. Chapter 02's
  // float layout (with our depth format) so that only rounding separates forward and deferred:
  // 1 step (GBufferGl.FloatLayoutEqualsForwardUpToRounding), and 1 more for chapter 03's cut
  // of each local light below one step, which the forward loop does not cut.
  const ch02::Layout layout = ch02::float_reference_for(ch02::our_layout());
  World glass(with_glass_alpha(1.f), layout), opaque(with_glass_alpha(1.f, false), layout);
  for (const char* view : {"front", "side"}) {
    const ImageRGBA8 truth = opaque.render(view, Method::Off);
    const ExactComposite exact = glass.exact(view);
    const std::vector<int> sorted = steps(glass.render(view, Method::Sorted), truth);
    const std::vector<int> wboit = steps(glass.render(view, Method::Wboit, DrawOrder::AsListed), truth);
    std::size_t compared = 0;
    for (std::size_t i = 0; i < sorted.size(); ++i) {
      if (exact.layers[i] == 0 || !exact.surface_order_right[i]) continue;  // the X: any order of whole panes is wrong
      ++compared;
      EXPECT_LE(sorted[i], 2) << view << ": sorted, pixel " << i;
      // WBOIT only where one layer: with alpha 1 the layers behind still weigh in (below).
      if (exact.layers[i] == 1) {
        EXPECT_LE(wboit[i], 2) << view << ": wboit, pixel " << i;
      }
    }
    EXPECT_GT(compared, 5000u) << view;
  }
}

// The atrium's floor (an albedo and a tangent-space normal map) made glass of alpha 1: through
// the stage it is the opaque floor of the G-buffer, normal map and all, within the 2 steps of
// the test above (chapter 02's float layout). Without the map read (the interpolated normal)
// the tiles' bevels would be flat: the floor drawn without its map is more than 2 steps off on
// many of its pixels, so this test fails if the glass ignores the map.
TEST(TransparencyGl, NormalMappedGlassOfAlphaOneEqualsTheOpaquePath) {
  auto atrium = [](bool blend, bool normal_map) {
    Scene s = load_scene(from_root("assets/atrium/atrium.gltf"));
    std::size_t mapped = 0;
    for (Material& m : s.materials)
      if (m.normal_texture >= 0) {
        ++mapped;
        m.blend = blend;
        m.base_color.a = 1.f;
        if (!normal_map) m.normal_texture = -1;
      }
    EXPECT_EQ(mapped, 1u) << "the atrium's tiled floor";
    return s;
  };
  const ch02::Layout layout = ch02::float_reference_for(ch02::our_layout());
  World glass(atrium(true, true), layout), opaque(atrium(false, true), layout), flat(atrium(false, false), layout);
  const ImageRGBA8 truth = opaque.render("aisle", Method::Off);
  const ExactComposite exact = glass.exact("aisle");
  const std::vector<int> sorted = steps(glass.render("aisle", Method::Sorted), truth);
  const std::vector<int> unmapped = steps(flat.render("aisle", Method::Off), truth);
  std::size_t floor = 0, off = 0, bevels = 0;
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    if (exact.layers[i] == 0) continue;  // not the floor
    ++floor;
    if (sorted[i] > 2) ++off;
    if (unmapped[i] > 2) ++bevels;
  }
  EXPECT_GT(floor, std::size_t(kW * kH / 4));
  EXPECT_EQ(off, 0u) << "of " << floor << " floor pixels";
  EXPECT_GT(bevels, floor / 20) << "the normal map changes the floor's light by more than 2 steps on 5 % of it";
}

TEST(TransparencyGl, APaneBehindTheWallIsHidden) {
  // The hidden pane (behind the wall) fails the depth test against the G-buffer everywhere:
  // making it clear changes no pixel of either method, nor the number of fragments captured.
  Scene clear = glass_scene();
  for (Material& m : clear.materials)
    if (m.name == "glass_hidden") m.base_color.a = 0.f;
  World seen(glass_scene()), cleared(std::move(clear));
  for (const char* view : {"front", "side"}) {
    EXPECT_EQ(seen.render(view, Method::Sorted).pixels, cleared.render(view, Method::Sorted).pixels) << view;
    EXPECT_EQ(seen.render(view, Method::Wboit).pixels, cleared.render(view, Method::Wboit).pixels) << view;
    Scene without = glass_scene();
    std::erase_if(without.instances, [](const Instance& i) { return i.name == "pane_hidden"; });
    World removed(std::move(without));
    EXPECT_EQ(seen.exact(view).fragments, removed.exact(view).fragments) << view;
  }
}

TEST(TransparencyGl, SixtyFourLayersStayFiniteAndClose) {
  // 64 copies of the green pane 1 cm apart: the accumulation stays finite, and as every layer
  // has the same colour WBOIT's average is that colour, up to the half floats' rounding of two
  // sums of 64 terms: each add rounds by at most 2^-12 relative, so the ratio is within
  // 2 * 64 * 2^-12 = 3.1 % in linear light, 1.3 % in sRGB (the curve's exponent 1/2.4), at
  // most 3.3 of 255 steps; with the two roundings into 8 bits, at most 5 steps.
  Scene s = glass_scene();
  std::erase_if(s.instances, [&](const Instance& i) { return i.name.rfind("pane_", 0) == 0 || i.name.rfind("cross_", 0) == 0; });
  Scene base = glass_scene();
  const Instance green = *std::find_if(base.instances.begin(), base.instances.end(), [](const Instance& i) { return i.name == "pane_green"; });
  for (int k = 0; k < 64; ++k) {
    Instance copy = green;
    copy.model = glm::translate(glm::mat4(1), glm::vec3(0, 0, -0.01f * float(k))) * green.model;
    s.instances.push_back(copy);
  }
  World w(std::move(s));
  const ExactComposite exact = w.exact("front", 80);
  EXPECT_EQ(*std::max_element(exact.layers.begin(), exact.layers.end()), 64);
  const std::vector<int> d = steps(w.render("front", Method::Wboit, DrawOrder::AsListed), exact.image);
  std::vector<float> sum(std::size_t(kW) * kH * 4);
  glGetTextureImage(w.stage.accumulation(), 0, GL_RGBA, GL_FLOAT, GLsizei(sum.size() * sizeof(float)), sum.data());
  EXPECT_TRUE(std::all_of(sum.begin(), sum.end(), [](float v) { return std::isfinite(v) && v >= 0.f; }));
  EXPECT_LE(*std::max_element(d.begin(), d.end()), 5);
  const std::vector<int> sorted = steps(w.render("front", Method::Sorted), exact.image);
  // Sorted: 64 roundings, each shrunk by 0.4 in linear light after the next layer: the bound
  // (L + 1) / 2 holds (and it is far from tight here).
  for (std::size_t i = 0; i < sorted.size(); ++i) EXPECT_LE(sorted[i], sorted_bound(exact.layers[i])) << "pixel " << i;
}

TEST(TransparencyGl, TheWeightFallsWithDepthWithinItsClamp) {
  // The C++ wboit_weight (the formula the book states; the GLSL one is held by the images).
  EXPECT_FLOAT_EQ(wboit_weight(5.f, 1.f), 10.f / (1e-5f + 1.f + std::pow(5.f / 200.f, 6.f)));
  EXPECT_FLOAT_EQ(wboit_weight(0.01f, 0.5f), 0.5f * 3e3f);   // clamped near
  EXPECT_FLOAT_EQ(wboit_weight(1e4f, 1.f), 1e-2f);           // clamped far
  EXPECT_GT(wboit_weight(1.f, 1.f), wboit_weight(2.f, 1.f));  // nearer weighs more
}

TEST(TransparencyGl, GlassBeforeTheSkyBlendsOverTheBackground) {
  // Looking up past the panes' tops over the wall: there the G-buffer holds no surface (the
  // depth is the cleared far value) and the glass blends over the background colour. Sorted
  // and WBOIT must keep their bounds there as anywhere.
  World w(glass_scene());
  Camera up;
  up.world = glm::inverse(glm::lookAt(glm::vec3(-0.5f, 0.2f, 2.5f), glm::vec3(-0.5f, 2.6f, 0.f), glm::vec3(0, 1, 0)));
  up.yfov = 0.9f, up.znear = 0.05f, up.zfar = 100.f;
  const FrameCamera cam = frame_camera(up, float(kW) / kH);
  w.render(cam, {.method = Method::Off});
  const ImageRGBA8 opaque = w.target.read();
  ExactComposite exact = w.stage.exact_composite(w.frame);
  ASSERT_FALSE(exact.overflow);
  const ImageRGBA8 sorted = w.render(cam, {.method = Method::Sorted});
  const ImageRGBA8 wboit = w.render(cam, {.method = Method::Wboit, .order = DrawOrder::AsListed});
  const std::vector<int> sorted_error = steps(sorted, exact.image), wboit_error = steps(wboit, exact.image);
  const std::vector<int> glass_shows = steps(sorted, opaque);
  const glm::vec3 b = ch01::kBackground;
  const int bg[3] = {int(std::lround(linear_to_srgb(b.r) * 255)), int(std::lround(linear_to_srgb(b.g) * 255)),
                     int(std::lround(linear_to_srgb(b.b) * 255))};
  std::size_t before_sky = 0, changed = 0;
  for (std::size_t i = 0; i < exact.layers.size(); ++i) {
    const bool background = std::abs(opaque.pixels[i * 4] - bg[0]) <= 1 && std::abs(opaque.pixels[i * 4 + 1] - bg[1]) <= 1 &&
                            std::abs(opaque.pixels[i * 4 + 2] - bg[2]) <= 1;
    if (!background || exact.layers[i] == 0) continue;
    ++before_sky;
    if (exact.surface_order_right[i]) {
      EXPECT_LE(sorted_error[i], sorted_bound(exact.layers[i])) << "pixel " << i;
    }
    if (exact.layers[i] == 1) {
      EXPECT_LE(wboit_error[i], 1) << "pixel " << i;
    }
    changed += glass_shows[i] > 0;
  }
  std::printf("  %zu pixels of glass before the sky, %zu changed by it\n", before_sky, changed);
  EXPECT_GT(before_sky, 200u) << "the view should see glass against the sky";
  EXPECT_GT(changed, before_sky * 9 / 10) << "the glass shows against the sky";
}

namespace {
// A stage whose own pass, after the lights, leaves a texel of 1 (the far plane, lit) on every
// unit the stages may get, as chapter 08's pass once left its indirect light on the unit
// chapter 06's map is read from.
struct ClobberingStage : ch03::FrameStage {
  gl::Texture far = gl::make_texture_2d(GL_R32F, 1, 1);
  ClobberingStage() {
    const float one = 1.f;
    glTextureSubImage2D(far.id(), 0, 0, 0, 1, 1, GL_RED, GL_FLOAT, &one);
  }
  void add_light(ch03::DeferredFrame&, PassMetrics*) override {
    for (GLuint unit = ch03::DeferredFrame::kFirstStageUnit; unit < 32; ++unit) glBindTextureUnit(unit, far.id());
  }
};
}  // namespace

// The glass is drawn after every other stage's pass, so it binds the frame's hook resources
// itself (DeferredFrame::bind_hooks()) before it reads the sun's map: a stage that left other
// textures on those units changes no pixel. The atrium's floor as glass of alpha 1 (its own
// colour, nothing behind), with chapter 06's shadows; without them the floor is brighter, so
// the map is really read.
TEST(TransparencyGl, TheGlassReadsTheShadowMapWhateverAStageLeftOnItsUnits) {
  Scene scene = load_scene(from_root("assets/atrium/atrium.gltf"));
  for (Material& m : scene.materials)
    if (m.normal_texture >= 0) m.blend = true, m.base_color.a = 1.f;  // the tiled floor
  const SceneGpu gpu(scene);
  const FrameCamera cam = frame_camera(scene.camera("aisle"), float(kW) / kH);
  auto draw = [&](bool shadows, bool clobber) {
    ch03::DeferredFrame frame(gpu);
    ch03::use_lights(frame, scene, scene.lights, false);
    ch06::ShadowStage map(gpu, ch06::find_sun(scene));
    ClobberingStage clobbering;
    TransparencyStage glass(frame, gpu);
    if (shadows) frame.add_stage(map);
    if (clobber) frame.add_stage(clobbering);
    frame.add_stage(glass);
    OutputTarget target(kW, kH);
    frame.render(cam, {target.framebuffer(), kW, kH});
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    return target.read();
  };
  const ImageRGBA8 shadowed = draw(true, false), clobbered = draw(true, true), unshadowed = draw(false, false);
  EXPECT_TRUE(clobbered.pixels == shadowed.pixels) << compare(clobbered, shadowed).summary();
  EXPECT_GT(compare(unshadowed, shadowed, {.threshold = 3, .max_failing_fraction = 0}).failing_fraction, 0.05)
      << "the sun's map darkens part of the floor";
}

// When the frame's local lights are chapter 09's clusters, built for every cell (the whole
// frame with glass), the glass reads those lists instead of building a second set: no pass of
// its own, and the image of the glass with lists of its own, bit for bit (a cell's list is the
// same whoever builds it). Lists of the occupied cells only would leave a pane in an empty
// cell unlit: refused.
TEST(TransparencyGl, TheGlassReadsTheFramesClustersInsteadOfBuildingItsOwn) {
  World w(glass_scene());
  ch09::ClusteredLights clusters(w.frame.volumes(), {.kind = ch09::CullKind::Clustered, .all_cells = true});
  w.frame.set_local_lights(&clusters);
  const FrameCamera camera = w.camera("front");
  const std::string own_pass = "transparency: light lists (chapter 09, every cluster)";
  auto render = [&](ch09::ClusteredLights* frame_lists, bool& built_own) {
    w.stage.use_frame_lists(frame_lists);
    w.stage.set({.method = Method::Sorted});
    PassMetrics metrics;
    w.frame.render(camera, {w.target.framebuffer(), kW, kH}, &metrics);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    built_own = metrics.find(own_pass) != nullptr;
    return w.target.read();
  };
  bool own_built = false, shared_built = true;
  const ImageRGBA8 shared = render(&clusters, shared_built);  // first: no lists of its own exist yet
  const ImageRGBA8 own = render(nullptr, own_built);
  EXPECT_TRUE(own_built);
  EXPECT_FALSE(shared_built);
  const std::vector<int> d = steps(shared, own);
  EXPECT_EQ(*std::max_element(d.begin(), d.end()), 0);
  ch09::ClusteredLights occupied_only(w.frame.volumes(), {.kind = ch09::CullKind::Clustered});
  EXPECT_THROW(w.stage.use_frame_lists(&occupied_only), Error);
  w.stage.use_frame_lists(nullptr);
}

// Many near layers overflow the half-float accumulation to infinity (w alpha c up to 3e3 a
// layer: 22 white layers pass 65504). In an 8-bit target that reads as white either way, but
// an HDR target keeps the infinity and the tone curve turns it into NaN (inf / (1 + inf)). The
// composite's min() keeps the average finite: with sum.rgb and sum.a both infinite it gives
// 65504 / 5e4 (the alpha sum's clamp), whatever the colour. Run on the composite shader itself
// (u_show 0, no blending) into a float target: an overflowed pixel and an ordinary one, whose
// average is the sum's ratio to half-float rounding (2^-11).
TEST(TransparencyGl, TheCompositeStaysFiniteWhereTheHalfFloatSumOverflows) {
  const float inf = std::numeric_limits<float>::infinity();
  const float accumulation[2][4] = {{inf, inf, 0.f, inf}, {2.f, 1.f, 0.5f, 4.f}};
  const float revealage[2] = {0.f, 0.5f};
  gl::Texture accum = gl::make_texture_2d(GL_RGBA16F, 2, 1), reveal = gl::make_texture_2d(GL_R16F, 2, 1);
  glTextureSubImage2D(accum.id(), 0, 0, 0, 2, 1, GL_RGBA, GL_FLOAT, accumulation);
  glTextureSubImage2D(reveal.id(), 0, 0, 0, 2, 1, GL_RED, GL_FLOAT, revealage);
  gl::Texture target = gl::make_texture_2d(GL_RGBA32F, 2, 1);
  gl::Framebuffer fb;
  glNamedFramebufferTexture(fb.id(), GL_COLOR_ATTACHMENT0, target.id(), 0);
  ShaderProgram composite({{GL_VERTEX_SHADER, "02_gbuffer/shaders/fullscreen.vert"},
                           {GL_FRAGMENT_SHADER, "10_frame/shaders/wboit_composite.frag"}});
  gl::VertexArray vao;
  glBindFramebuffer(GL_FRAMEBUFFER, fb.id());
  glViewport(0, 0, 2, 1);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glBindTextureUnit(0, accum.id());
  glBindTextureUnit(1, reveal.id());
  composite.use();
  composite.set("u_show", 0);
  glBindVertexArray(vao.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  float out[2][4] = {};
  glGetTextureImage(target.id(), 0, GL_RGBA, GL_FLOAT, sizeof out, out);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  for (float v : out[0]) EXPECT_TRUE(std::isfinite(v)) << "the overflowed pixel: " << out[0][0] << " " << out[0][1];
  EXPECT_NEAR(out[0][0], 65504.f / 5e4f, 1e-3f);
  const float expected[4] = {0.25f, 0.125f, 0.0625f, 0.5f};  // (2, 1, 0.5) / 4 x (1 - 0.5), alpha 1 - 0.5
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(out[1][k], expected[k], expected[k] * 0x1p-11f) << k;
}
