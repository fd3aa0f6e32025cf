// Chapter 08's pass on the GPU (llvmpipe in CI) against the ray-traced one-bounce truth: the
// Cornell box's colour bleeding, the patterns, the second bounce, and the hard cases. Bounds are
// stated where they are asserted; they hold on any conforming renderer.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/08_ssgi/gi_frame.h"
#include "chapters/07_ssao/ao_truth.h"
#include "chapters/08_ssgi/gi_truth.h"
#include "chapters/08_ssgi/guard_band.h"
#include "common/target.h"
#include <algorithm>
#include "common/error.h"
#include "common/paths.h"
#include "common/raytrace.h"
#include "tests/unit/book_data.h"
#include "tests/unit/gl_environment.h"
#include "tests/unit/squares_scene.h"

using namespace lp;
using namespace lp::ch08;
using lp::test::book_row;

namespace {

constexpr int kW = 160, kH = 90;

struct World {
  explicit World(const std::string& file, float light_scale = 1.f)
      : scene(scaled(load_scene(from_root(file)), light_scale)), gpu(scene), frame(gpu, kW, kH) {}
  explicit World(Scene s) : scene(std::move(s)), gpu(scene), frame(gpu, kW, kH) {}
  static Scene scaled(Scene s, float light_scale) {
    for (Light& l : s.lights) l.intensity *= light_scale;
    return s;
  }
  FrameCamera camera(const std::string& view) const { return frame_camera(scene.camera(view), float(kW) / kH); }
  // The instance each pixel sees (its name), from the ray tracer's primary hits (the raster's pixels).
  // With `near_x` > 0, only the points within near_x of the left (name "<", x < -1 + near_x) or
  // right (">": x > 1 - near_x) wall of the box keep their name ("floor<", "floor>").
  std::vector<std::string> names(const FrameCamera& cam, float near_x = 0.f) const {
    RayScene rays(scene);
    std::vector<std::string> n;
    for (const auto& h : primary_hits(rays, cam, kW, kH)) {
      std::string name = h ? scene.instances[std::size_t(h->instance)].name : "";
      if (h && near_x > 0.f) name += h->position.x < -1.f + near_x ? "<" : h->position.x > 1.f - near_x ? ">" : "";
      n.push_back(name);
    }
    return n;
  }
  Scene scene;
  SceneGpu gpu;
  GiFrame frame;
};

World& cornell() {
  // never destroyed: its GL objects must not outlive the test environment's context
  static World* w = new World("assets/cornell/cornell.gltf");
  return *w;
}

// The truth at 160x90: 1024 cosine-weighted rays per pixel.
ImageF truth(World& w, const FrameCamera& cam, GiTruthSettings s = {.samples = 1024}) {
  return cached_ray_traced_indirect(w.scene, w.frame.lights(), cam, kW, kH, s);
}

// Mean of channel c over the pixels that see `name` and lie in columns [x0, x1).
double region_mean(const ImageF& img, const std::vector<std::string>& names, const std::string& name, int c, int x0 = 0,
                   int x1 = kW) {
  double sum = 0;
  long n = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = x0; x < x1; ++x)
      if (names[std::size_t(y) * kW + x] == name) {
        sum += img.at(x, y, c);
        ++n;
      }
  return n ? sum / double(n) : std::nan("");
}

// A camera at `eye` looking at `at`, with the Cornell view's lens.
FrameCamera look(World& w, glm::vec3 eye, glm::vec3 at, glm::vec3 up = glm::vec3(0, 1, 0)) {
  FrameCamera c = w.camera("front");
  c.view = glm::lookAt(eye, at, up);
  c.position = eye;
  return c;
}

// The colour bleeding of one region: how much redder than the light its indirect light is,
// R - G / 0.93 (the Cornell light is (1, 0.93, 0.8): light off a white wall gives 0; off the red
// wall > 0, off the green wall < 0).
double red_excess(const ImageF& img, const std::vector<std::string>& names, const std::string& name, int x0 = 0,
                  int x1 = kW) {
  return region_mean(img, names, name, 0, x0, x1) - region_mean(img, names, name, 1, x0, x1) / 0.93;
}

bool all_finite(const ImageF& img) {
  for (float v : img.data)
    if (!std::isfinite(v)) return false;
  return true;
}

// The most any pixel can receive: the form factors from a point sum to at most 1 (the pass
// scales them back when its disks overlap), so L1_ind <= max over the screen of albedo x L1.
// The light buffer's L1 with no stage light (mode off, ambient 0) times the G-buffer's largest
// albedo in the scene (0.78, the light patch) bounds it.
float brightest_emitter(World& w, const FrameCamera& cam, float albedo = 0.78f) {
  w.frame.frame().set_ambient(glm::vec3(0));
  w.frame.image(cam, GiMode::Off, {}, GiShow::Image, 0.f);
  ImageF l = ImageF::blank(kW, kH, 4);
  glGetTextureImage(w.frame.frame().light().diffuse(), 0, GL_RGBA, GL_FLOAT, GLsizei(l.data.size() * sizeof(float)),
                    l.data.data());
  w.frame.frame().set_ambient(w.scene.ambient);
  float most = 0.f;
  for (std::size_t i = 0; i < l.data.size(); ++i)
    if (i % 4 != 3) most = std::max(most, l.data[i]);
  return most * albedo;
}

float largest_rgb(const ImageF& img) {
  float most = 0.f;
  for (std::size_t i = 0; i < img.data.size(); ++i)
    if (i % std::size_t(img.channels) < 3) most = std::max(most, img.data[i]);
  return most;
}

GiErrors cornell_errors(const GiSettings& s) {
  World& w = cornell();
  const FrameCamera cam = w.camera("front");
  GiErrors e = gi_errors(w.frame.indirect(cam, GiMode::Ssgi, s), truth(w, cam));
  std::cout << kPatternNames[int(s.pattern)] << " " << s.samples << " samples: mean abs " << e.mean_abs << ", relative "
            << e.relative << ", captured " << e.captured << "\n";
  return e;
}

}  // namespace

// [bleeding]
// Colour bleeding in the Cornell box, 128 samples, randomised + blurred. The red wall reddens
// the floor within 0.3 of it and the tall box's face toward it; the green wall greens the short
// box's face toward it. Each region's bleeding (red_excess) must have the truth's sign and
// between 0.3 and 1.3 times its size. Why these bounds: the pass finds only what the screen
// shows within R_gi (the screen-limited truth: 0.91 of the true energy here, and all of it in
// these regions), and 128 samples find 0.92 of that over the image (ConvergesToWhatTheScreenShows);
// but where the emitter touches the receiver (the floor in the red wall's corner, the box faces
// beside the floor) one sample disk stands for a large patch whose cosines, taken at its centre,
// are near 0: the pass finds 0.42 to 0.65 of the bleeding there (llvmpipe). The upper bound 1.3
// allows for light the pass counts through occluders (it has no visibility term). A pass that
// bled the wrong colour, or none (mode ssao gives 0), or counted twice fails.
TEST(SsgiCornell, ColourBleedingHasTheTruthsSignAndMagnitude) {
  World& w = cornell();
  const FrameCamera cam = w.camera("front");
  const auto names = w.names(cam);
  const ImageF t = truth(w, cam);
  const ImageF gi = w.frame.indirect(cam, GiMode::Ssgi, {.samples = 128, .pattern = Pattern::Randomised});
  struct Region {
    const char* name;
    int x0, x1;
    double sign;
  };
  const auto near = w.names(cam, 0.3f);
  for (Region r : {Region{"floor<", 0, kW, 1}, Region{"tall_box_nx", 0, kW, 1},
                   Region{"short_box_px", 0, kW, -1}}) {
    const double want = red_excess(t, near, r.name, r.x0, r.x1), got = red_excess(gi, near, r.name, r.x0, r.x1);
    std::cout << r.name << ": bleeding " << got << ", truth " << want << "\n";
    EXPECT_GT(want * r.sign, 0.02) << r.name;  // the truth bleeds there (well above its noise, 0.008)
    EXPECT_GT(got * r.sign, 0.3 * want * r.sign) << r.name << " [" << r.x0 << ", " << r.x1 << ")";
    EXPECT_LT(got * r.sign, 1.3 * want * r.sign) << r.name << " [" << r.x0 << ", " << r.x1 << ")";
  }
  // The floor beside the green wall is where the missing visibility shows: the truth bleeds green
  // there, the pass about nothing, because it also receives the red wall's light through the short
  // box: its red is more than 1.1x the truth's and more than 1.1x its own green's share (measured
  // 1.33x and 1.13x: red / green 1.18 on llvmpipe). A visibility-aware gather cuts it (Gather::Bitmask:
  // BitmaskCutsTheLightThroughTheShortBox).
  {
    const double red = region_mean(gi, near, "floor>", 0) / region_mean(t, near, "floor>", 0);
    const double green = region_mean(gi, near, "floor>", 1) / region_mean(t, near, "floor>", 1);
    std::cout << "floor beside the green wall: red x" << red << ", green x" << green << " of the truth\n";
    EXPECT_LT(red_excess(t, near, "floor>"), -0.02);
    EXPECT_GT(red, 1.1);
    EXPECT_GT(red / green, 1.1);
  }
  // the same frame without the wide disk bleeds nothing
  const ImageF ao_only = w.frame.indirect(cam, GiMode::Ssao, {.samples = 64});
  EXPECT_EQ(largest_rgb(ao_only), 0.f);
}
// [/bleeding]

// [bitmask-test]
// Beyond the source: the same case with the wide disk gathered along slices with a visibility
// bitmask (Gather::Bitmask, 128 samples: 8 slices of 2 x 8 steps). On the floor beside the green
// wall the source's pass gets the red wall's light through the short box; the bitmask, whose
// nearer samples (the short box) hide the farther (the red wall), must cut that wrongly received
// red, the pass's red minus the truth's, to at most 0.4 of the source's (measured 0.17 on
// llvmpipe: 0.0070 against 0.0414; the margin for other renderers and the noise of the
// randomised slices). And where colour bleeding is visible it must not break it: the regions of
// ColourBleedingHasTheTruthsSignAndMagnitude keep the truth's sign, and its mean absolute error
// against the truth over the Cornell box may exceed the source's by at most 20 % (measured 1.12x:
// the slabs, 0.5 deep, also hide some light the truth receives past thin edges and at grazing
// angles; it captures 0.76 of the true energy against the source's 0.83). A bound of 10 % was
// tried first and failed at 1.12: the variant is not free, and the book says so.
TEST(SsgiCornell, BitmaskCutsTheLightThroughTheShortBox) {
  World& w = cornell();
  const FrameCamera cam = w.camera("front");
  const auto near = w.names(cam, 0.3f);
  const ImageF t = truth(w, cam);
  const GiSettings source{.samples = 128, .pattern = Pattern::Randomised};
  GiSettings bitmask = source;
  bitmask.gather = Gather::Bitmask;
  const ImageF a = w.frame.indirect(cam, GiMode::Ssgi, source);
  const ImageF b = w.frame.indirect(cam, GiMode::Ssgi, bitmask);
  const double want = region_mean(t, near, "floor>", 0);
  const double wrong_source = region_mean(a, near, "floor>", 0) - want;
  const double wrong_bitmask = region_mean(b, near, "floor>", 0) - want;
  const GiErrors ea = gi_errors(a, t), eb = gi_errors(b, t);
  std::cout << "floor beside the green wall, red above the truth: disk " << wrong_source << ", bitmask " << wrong_bitmask
            << " (x" << wrong_bitmask / wrong_source << ")\n"
            << "Cornell box mean abs error: disk " << ea.mean_abs << ", bitmask " << eb.mean_abs << " (x"
            << eb.mean_abs / ea.mean_abs << "); captured " << ea.captured << " / " << eb.captured << "\n";
  for (const char* r : {"floor<", "tall_box_nx", "short_box_px"})
    std::cout << r << ": bleeding disk " << red_excess(a, near, r) << ", bitmask " << red_excess(b, near, r)
              << ", truth " << red_excess(t, near, r) << "\n";
  ASSERT_GT(wrong_source, 0.0);  // the flaw is there to cut (SsgiCornell.ColourBleeding... asserts its size)
  EXPECT_LT(wrong_bitmask, 0.4 * wrong_source);
  EXPECT_LT(eb.mean_abs, 1.20 * ea.mean_abs);
  EXPECT_GT(red_excess(b, near, "floor<"), 0.0);
  EXPECT_GT(red_excess(b, near, "tall_box_nx"), 0.0);
  EXPECT_LT(red_excess(b, near, "short_box_px"), 0.0);
}
// [/bitmask-test]

// [samples]
// The error against the truth falls as samples grow, for every pattern (16 -> 64 -> 128), and
// the randomised pattern with its blur is closer than the regular grid at 16 samples (the
// grid's bands: measured 0.47 against 0.63 relative error). The truth's own noise is far below
// every error: two truths of 1024 rays with other seeds differ by 0.011 mean absolute (each
// 0.011 / sqrt 2 = 0.008 from the expectation), a fifth of the smallest error here (0.040).
TEST(SsgiCornell, MoreSamplesComeCloserToTheTruth) {
  for (Pattern p : {Pattern::Regular, Pattern::Spiral, Pattern::Randomised}) {
    double e16 = cornell_errors({.samples = 16, .pattern = p}).mean_abs;
    double e64 = cornell_errors({.samples = 64, .pattern = p}).mean_abs;
    double e128 = cornell_errors({.samples = 128, .pattern = p}).mean_abs;
    EXPECT_LT(e64, e16) << kPatternNames[int(p)];
    EXPECT_LT(e128, e64) << kPatternNames[int(p)];
    EXPECT_GT(e128, 0.03) << "closer than the truth's noise allows: " << kPatternNames[int(p)];
  }
  EXPECT_LT(cornell_errors({.samples = 16, .pattern = Pattern::Randomised}).relative,
            0.85 * cornell_errors({.samples = 16, .pattern = Pattern::Regular}).relative);
}
TEST(SsgiCornell, TruthNoiseIsFarBelowTheErrors) {
  World& w = cornell();
  const FrameCamera cam = w.camera("front");
  GiErrors noise = gi_errors(truth(w, cam, {.samples = 1024, .seed = 99}), truth(w, cam));
  std::cout << "two truths differ by " << noise.mean_abs << " mean absolute\n";
  EXPECT_LT(noise.mean_abs / std::sqrt(2.0), 0.25 * cornell_errors({.samples = 128, .pattern = Pattern::Randomised}).mean_abs);
}
// [/samples]

// The screen-limited truth (only what the camera sees within R_gi) is what the pass
// approximates: with 128 samples it finds between 0.8 and 1.1 of its energy (measured 0.92).
TEST(SsgiCornell, ConvergesToWhatTheScreenShows) {
  World& w = cornell();
  const FrameCamera cam = w.camera("front");
  const ImageF screen = truth(w, cam, {.samples = 256, .screen_limited = true});  // sums over the image
  GiErrors e = gi_errors(w.frame.indirect(cam, GiMode::Ssgi, {.samples = 128, .pattern = Pattern::Randomised}), screen);
  std::cout << "against the screen-limited truth: captured " << e.captured << ", relative " << e.relative << "\n";
  EXPECT_GT(e.captured, 0.8);
  EXPECT_LT(e.captured, 1.1);
  EXPECT_LT(gi_errors(screen, truth(w, cam, {.samples = 256})).captured, 1.0);  // the screen sees less than everything
}

// [second-bounce]
// A second pass bounces direct + first-bounce light once more. In the truth (one more
// cosine-weighted ray per hit) the second bounce adds 0.43 of the first in this white box; the
// pass adds less (measured 0.24: the first bounce it bounces is itself short), but it adds:
// between 0.1 and the truth's share.
TEST(SsgiCornell, SecondBounceAddsLessThanTheTruthsButAdds) {
  World& w = cornell();
  const FrameCamera cam = w.camera("front");
  // the ratio of two sums over the image: 256 rays are plenty
  const double truth_gain =
      gi_errors(truth(w, cam, {.samples = 256, .bounces = 2}), truth(w, cam, {.samples = 256})).captured;
  const ImageF one = w.frame.indirect(cam, GiMode::Ssgi, {.samples = 64, .pattern = Pattern::Randomised});
  const ImageF two = w.frame.indirect(cam, GiMode::Ssgi, {.samples = 64, .pattern = Pattern::Randomised, .bounces = 2});
  const double gain = gi_errors(two, one).captured;  // sum two / sum one
  std::cout << "second bounce: truth x" << truth_gain << ", the pass x" << gain << "\n";
  EXPECT_GT(truth_gain, 1.2);
  EXPECT_GT(gain, 1.1);
  EXPECT_LT(gain, truth_gain);
}
// [/second-bounce]

// The narrow disk is chapter 07's disk AO with the form factor: against chapter 07's truth
// (R = 0.5, 512 rays) it keeps chapter 07's bound for its disk method (0.13).
TEST(SsgiCornell, NarrowDiskIsChapter07sAo) {
  World& w = cornell();
  const FrameCamera cam = w.camera("front");
  const ImageF gi = w.frame.indirect(cam, GiMode::Ssgi, {.samples = 32});
  ImageF a = ImageF::blank(kW, kH, 1);
  for (int i = 0; i < kW * kH; ++i) a.data[std::size_t(i)] = gi.data[std::size_t(i) * 4 + 3];
  const ImageF t = ch07::cached_ray_traced_ao(w.scene, cam, kW, kH, {.radius = 0.5f, .samples = 512});
  ch07::AoErrors e = ch07::ao_errors(a, t);
  std::cout << "AO of the narrow disk: mean absolute error " << e.mean_abs << "\n";
  EXPECT_LT(e.mean_abs, 0.13);
}

// Mode off adds the constant ambient light after the lights instead of in chapter 03's global
// pass: the same sum in another order, so the image is chapter 03's within one 8-bit step.
TEST(SsgiCornell, ModeOffIsChapter03sImage) {
  World& w = cornell();
  const FrameCamera cam = w.camera("front");
  const ImageRGBA8 ours = w.frame.image(cam, GiMode::Off, {}, GiShow::Image, 10.f);
  ch03::DeferredFrame plain(w.gpu);
  plain.volumes().set_lights(w.frame.lights());
  plain.set_ambient(w.scene.ambient * 10.f);
  OutputTarget target(kW, kH);
  plain.render(cam, {target.framebuffer(), kW, kH});
  const ImageRGBA8 theirs = target.read();
  int worst = 0;
  for (std::size_t i = 0; i < ours.pixels.size(); ++i) worst = std::max(worst, std::abs(int(ours.pixels[i]) - int(theirs.pixels[i])));
  EXPECT_LE(worst, 1);
  EXPECT_NE(ours.pixels, w.frame.image(cam, GiMode::Ssgi, {}, GiShow::Image, 10.f).pixels);  // and SSGI changes it
}

// [hard-cases]
// The red wall entirely off screen (the camera above the floor's right half, looking down): in
// the truth the red wall still reddens the floor's left edge; the screen cannot show it, so the
// pass loses it. Documented loss, bounded: the pass's red bleeding there is below a fifth of the
// truth's, as the screen-limited truth's is, and it invents no light: its total stays below 1.3x
// the screen-limited truth's.
TEST(SsgiHardCases, EmitterEntirelyOffScreenIsLost) {
  World& w = cornell();
  const FrameCamera cam = look(w, glm::vec3(0.4f, 1.9f, 0.2f), glm::vec3(0.4f, 0.f, 0.2f), glm::vec3(0, 0, -1));
  const auto names = w.names(cam);
  // 256 rays: the test reads means over some 2 700 pixels, where their noise (0.015 a pixel)
  // averages to below 0.001
  const ImageF t = truth(w, cam, {.samples = 256}), screen = truth(w, cam, {.samples = 256, .screen_limited = true});
  const ImageF gi = w.frame.indirect(cam, GiMode::Ssgi, {.samples = 64, .pattern = Pattern::Randomised});
  const double want = red_excess(t, names, "floor", 0, 30), seen = red_excess(screen, names, "floor", 0, 30);
  const double got = red_excess(gi, names, "floor", 0, 30);
  std::cout << "off-screen red wall: truth " << want << ", screen-limited " << seen << ", pass " << got << "\n";
  EXPECT_GT(want, 0.01);
  EXPECT_LT(seen, 0.2 * want);
  EXPECT_LT(got, 0.2 * want);
  EXPECT_LT(gi_errors(gi, screen).captured, 1.3);
}

// The sky (tests/data/minimal.gltf: one plane and the sky around it): nothing bounces between
// the plane and itself (every sample lies in its tangent plane: cos = 0, up to the depth's
// rounding, bound 1e-3 of the plane's own light) and nothing to or from the sky: no NaN, the
// sky's pixels 0, the AO 1 (to 0.995, chapter 07's bound).
TEST(SsgiHardCases, SkySendsAndReceivesNothing) {
  World w("tests/data/minimal.gltf");
  const FrameCamera cam = w.camera("view");
  const ImageF gi = w.frame.indirect(cam, GiMode::Ssgi, {.samples = 64, .pattern = Pattern::Randomised});
  ASSERT_TRUE(all_finite(gi));
  EXPECT_LE(largest_rgb(gi), 1e-3f * std::max(brightest_emitter(w, cam), 1e-3f));
  float lowest_ao = 1.f;
  for (std::size_t i = 3; i < gi.data.size(); i += 4) lowest_ao = std::min(lowest_ao, gi.data[i]);
  EXPECT_GE(lowest_ao, 0.995f);
}

// A light 1000x brighter, the camera close to the floor beside the tall box's base: no
// fireflies. The pass is linear in the light, so every pixel's indirect light is exactly 1000x
// what the normal light gives, up to half-float rounding (11 bits: 5e-4 relative per value, a
// few roundings per sum: bound 1 %, and 1e-3 absolute at the normal light for the darkest pixels);
// nothing saturates or switches on brightness. And no pixel gets more than the brightest emitter
// on screen sends (the transfers sum to at most 1). None is NaN.
TEST(SsgiHardCases, BrightEmitterNextToADarkReceiverMakesNoFireflies) {
  World bright("assets/cornell/cornell.gltf", 1000.f);
  World& normal = cornell();
  const FrameCamera cam = look(normal, glm::vec3(-0.2f, 0.5f, 0.6f), glm::vec3(-0.4f, 0.2f, -0.1f));
  const GiSettings s{.samples = 32, .pattern = Pattern::Randomised};
  const ImageF hot = bright.frame.indirect(cam, GiMode::Ssgi, s), cool = normal.frame.indirect(cam, GiMode::Ssgi, s);
  ASSERT_TRUE(all_finite(hot));
  EXPECT_LE(largest_rgb(hot), brightest_emitter(bright, cam));
  double worst = 0;
  for (std::size_t i = 0; i < hot.data.size(); ++i) {
    if (i % 4 == 3) continue;
    const double want = 1000.0 * cool.data[i];
    worst = std::max(worst, std::abs(hot.data[i] - want) / std::max(want, 1.0));
  }
  std::cout << "bright light: worst deviation from 1000x " << worst << "\n";
  EXPECT_LT(worst, 0.01);
}

// Grazing angles: the camera 5 cm above the floor looking along it. The floor's pixels are
// long slivers; the sample area's slant clamp (0.2) keeps them finite. No NaN, within the
// energy bound, and the floor gets what the screen shows it within 0.5 .. 1.5 (measured 0.98 on
// llvmpipe). Most of its true light comes from the ceiling and the upper walls, off screen: the
// screen-limited truth is 0.018 of the truth, the documented loss.
TEST(SsgiHardCases, GrazingAnglesStayBounded) {
  World& w = cornell();
  const FrameCamera cam = look(w, glm::vec3(0.f, 0.05f, 0.95f), glm::vec3(0.f, 0.05f, -1.f));
  const auto names = w.names(cam);
  const ImageF gi = w.frame.indirect(cam, GiMode::Ssgi, {.samples = 64, .pattern = Pattern::Randomised});
  ASSERT_TRUE(all_finite(gi));
  EXPECT_LE(largest_rgb(gi), brightest_emitter(w, cam));
  const ImageF t = truth(w, cam, {.samples = 256}), screen = truth(w, cam, {.samples = 256, .screen_limited = true});
  const double got = region_mean(gi, names, "floor", 1), seen = region_mean(screen, names, "floor", 1);
  const double want = region_mean(t, names, "floor", 1);
  std::cout << "grazing floor: pass " << got << ", screen-limited truth " << seen << ", truth " << want << "\n";
  EXPECT_GT(got, 0.5 * seen);
  EXPECT_LT(got, 1.5 * seen);
  EXPECT_LT(seen, 0.05 * want);
}

// The camera 6 cm from the back wall, looking at it: the whole screen is one plane, so the
// wide disk (clamped to the image height) finds nothing that faces the pixel: the pass gives
// almost nothing (below 5 % of the truth, which comes from the floor, ceiling and walls off
// screen: the documented loss), no NaN, and the AO of a plane: 1 (to 0.99).
TEST(SsgiHardCases, CameraAgainstAWallFindsNothingAndBreaksNothing) {
  World& w = cornell();
  const FrameCamera cam = look(w, glm::vec3(0.f, 1.f, -0.94f), glm::vec3(0.f, 1.f, -1.f));
  const ImageF gi = w.frame.indirect(cam, GiMode::Ssgi, {.samples = 64, .pattern = Pattern::Randomised});
  ASSERT_TRUE(all_finite(gi));
  const GiErrors e = gi_errors(gi, truth(w, cam, {.samples = 256}));
  std::cout << "against the wall: captured " << e.captured << " of " << e.mean_truth << "\n";
  EXPECT_GT(e.mean_truth, 0.05);
  EXPECT_LT(e.captured, 0.05);
  float lowest_ao = 1.f;
  for (std::size_t i = 3; i < gi.data.size(); i += 4) lowest_ao = std::min(lowest_ao, gi.data[i]);
  EXPECT_GE(lowest_ao, 0.99f);
}
// A thin object: a panel 1 cm thick (two back-to-back copies of the floor's 2x2 quad, 0.4 tall
// and 0.6 deep) standing on the floor of the Cornell box at x = -0.3, edge-on to the camera
// but for a sliver. In the truth it changes the floor beside it (measured: darker by 0.035: it
// hides more of the walls' light than its lit side adds); the pass sees a one- or two-pixel
// sliver of it and has no visibility term, so it changes almost nothing: documented loss,
// bounded. On the floor within 0.3 of it (the pixels that see the floor with and without it),
// the truth changes by more than 0.01 and the pass by less than half the truth's change;
// nothing is NaN; the energy bound holds.
TEST(SsgiHardCases, ThinObjectIsMostlyMissed) {
  World& plain = cornell();
  Scene scene = plain.scene;
  int floor_mesh = -1;
  for (const Instance& i : scene.instances)
    if (i.name == "floor") floor_mesh = i.mesh;
  ASSERT_GE(floor_mesh, 0);
  for (float side : {-1.f, 1.f}) {
    Instance panel{.name = "panel", .mesh = floor_mesh};
    panel.model = glm::translate(glm::mat4(1), glm::vec3(-0.3f + 0.005f * side, 0.4f, 0.35f)) *
                  glm::rotate(glm::mat4(1), -side * glm::half_pi<float>(), glm::vec3(0, 0, 1)) *
                  glm::scale(glm::mat4(1), glm::vec3(0.2f, 1.f, 0.3f));
    scene.instances.push_back(panel);
  }
  World w(std::move(scene));
  const FrameCamera cam = w.camera("front");
  const auto before = plain.names(cam), after = w.names(cam);
  RayScene rays(w.scene);
  const auto hits = primary_hits(rays, cam, kW, kH);
  const GiSettings s{.samples = 64};
  const ImageF pass0 = plain.frame.indirect(cam, GiMode::Ssgi, s), pass1 = w.frame.indirect(cam, GiMode::Ssgi, s);
  const ImageF truth0 = truth(plain, cam, {.samples = 256}), truth1 = truth(w, cam, {.samples = 256});
  ASSERT_TRUE(all_finite(pass1));
  EXPECT_LE(largest_rgb(pass1), brightest_emitter(w, cam));
  double d_pass = 0, d_truth = 0;
  long n = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const std::size_t i = std::size_t(y) * kW + x;
      if (before[i] != "floor" || after[i] != "floor" || std::abs(hits[i]->position.x + 0.3f) > 0.3f ||
          hits[i]->position.z < 0.f || hits[i]->position.z > 0.7f)
        continue;
      for (int c = 0; c < 3; ++c) {
        d_pass += pass1.at(x, y, c) - pass0.at(x, y, c);
        d_truth += truth1.at(x, y, c) - truth0.at(x, y, c);
      }
      ++n;
    }
  ASSERT_GT(n, 50);
  d_pass /= 3.0 * double(n);
  d_truth /= 3.0 * double(n);
  std::cout << "thin panel: the floor beside it changes by " << d_truth << " in the truth, " << d_pass << " in the pass ("
            << n << " pixels)\n";
  EXPECT_GT(std::abs(d_truth), 0.01);
  EXPECT_LT(std::abs(d_pass), 0.5 * std::abs(d_truth));
}

// [/hard-cases]

// The narrow disk's sample areas and its reach, where they matter: a roof 0.4 above the floor
// seen through a hole from 1 m above the floor (tests/unit/squares_scene.h; chapter 07's
// SsaoHardCases.RoofSeenThroughAHoleOccludesAsMuchAsItsTruth has the same case and says why).
// The floor's receivers see the roof at ze / zr = 0.6: a sample's share of the disk covers
// 0.36 of its area at the receiver's depth there (sample_area), and taken at the receiver's
// depth it makes the occlusion 2.8 times as large. The narrow disk is chapter 07's form factor
// with the same share, so it has chapter 07's bounds there: its mean occlusion over the floor's
// pixels within 0.8 .. 1.15 of the truth's (the losses that only lower it: saturation <= 2.3 %
// and the part of R's sphere its screen disk misses; the rest an allowance for the quadrature).
// The wide disk is off and its radius R_ao, so that the screen clamp (the image height) does
// not shorten the narrow one.
TEST(SsgiHardCases, RoofSeenThroughAHoleOccludesAsMuchAsItsTruth) {
  const test::RoofHole r;
  World w(test::roof_hole_scene(r));
  const FrameCamera cam = test::roof_hole_camera(r, float(kW) / kH);
  const GiSettings s{.indirect = false, .samples = 32, .ao_radius = 0.5f, .gi_radius = 0.5f, .blur = false};
  ASSERT_LT(s.ao_radius * cam.projection[1][1] * 0.5 * kH / r.eye, s.max_screen_radius * kH);  // no clamp
  const ImageF gi = w.frame.indirect(cam, GiMode::Ssgi, s);
  const ImageF t = ch07::cached_ray_traced_ao(w.scene, cam, kW, kH, {.radius = s.ao_radius, .samples = 512});
  const auto names = w.names(cam);
  double method = 0, want = 0;
  long pixels = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      if (names[std::size_t(y) * kW + x] != "floor") continue;
      method += 1.0 - gi.at(x, y, 3), want += 1.0 - t.at(x, y, 0), ++pixels;
    }
  method /= double(std::max(pixels, 1L)), want /= double(std::max(pixels, 1L));
  std::cout << "floor through the hole: mean occlusion " << method << ", truth " << want << " (" << method / want
            << " of it) over " << pixels << " pixels\n";
  ASSERT_GT(pixels, 500);  // the truth's mean good to 0.001
  ASSERT_GT(want, 0.1);
  EXPECT_GT(method, 0.8 * want);
  EXPECT_LT(method, 1.15 * want);
}

// The same scene with both radii 0.3, below the roof's height: no surface lies within R of
// another that is not in its plane (floor and roof are 0.4 apart, the roof's parts coplanar), so
// the AO is 1 everywhere, up to the depth's rounding in the plane (chapter 07's open plane,
// 0.995), and the indirect light 0 (every emitter within R in the receiver's plane: cos = 0, to
// 1e-3 of the brightest emitter, as SkySendsAndReceivesNothing). The floor's disks reach the
// roof's pixels on the screen, 0.4 .. 0.5 away in 3D: counted, they darken the floor.
TEST(SsgiHardCases, RoofBeyondTheRadiiSendsAndHidesNothing) {
  const test::RoofHole r;
  World w(test::roof_hole_scene(r));
  const FrameCamera cam = test::roof_hole_camera(r, float(kW) / kH);
  const GiSettings s{.samples = 32, .ao_radius = 0.3f, .gi_radius = 0.3f, .blur = false};
  ASSERT_LT(s.gi_radius, r.roof);
  const ImageF gi = w.frame.indirect(cam, GiMode::Ssgi, s);
  ASSERT_TRUE(all_finite(gi));
  float lowest_ao = 1.f;
  for (std::size_t i = 3; i < gi.data.size(); i += 4) lowest_ao = std::min(lowest_ao, gi.data[i]);
  std::cout << "radii below the roof: lowest A " << lowest_ao << ", largest L1_ind " << largest_rgb(gi) << "\n";
  EXPECT_GE(lowest_ao, 0.995f);
  EXPECT_LE(largest_rgb(gi), 1e-3f * std::max(brightest_emitter(w, cam), 1e-3f));
}

// The transfers' normalisation (ssgi.comp [ssgi-clamp]): the form factors from a point to
// surfaces that do not overlap sum to at most 1, but the pass's sample disks can overlap, most
// where a surface seen at a slant (its areas grown up to 5x) lies close to the receiver: the
// Cornell box's left wall beside the tall box sums to 1.5. Scaled back, a pixel's indirect
// light is a weighted mean of its emitters' albedo x L1, so where every emitter sends the same
// W it is at most W (to three half-float roundings, 2^-11 each: the result's and the two L1s'
// ratio). The case: a U
// between two walls 0.6 apart (tests/unit/squares_scene.h's squares), each wall lit by its own
// sun at 45 degrees (N.L = 0.707, the other sun behind it), the floor by both at half the
// walls' albedo, seen down the U from nine places: every emitter on the screen sends the same
// W. Not scaled back, the few pixels whose transfers sum past 1 (by up to 9 %, in about one
// view in three on llvmpipe: the randomised pattern's closest samples on a wall seen at a
// slant) get more than W.
Scene slot_scene(float gap, float height, float length) {
  Scene s = test::squares_scene("slot between two walls (test)");
  const glm::mat4 size = glm::scale(glm::mat4(1), glm::vec3(height, 1, length));
  const glm::vec3 lo(-0.5f * gap, 0, -length + 1), hi(0.5f * gap, height, 1);
  test::add_square(s, "left", glm::translate(glm::mat4(1), glm::vec3(lo.x, height, lo.z)) *
                                  glm::rotate(glm::mat4(1), -glm::half_pi<float>(), glm::vec3(0, 0, 1)) * size, lo, hi);
  test::add_square(s, "right", glm::translate(glm::mat4(1), glm::vec3(hi.x, 0, lo.z)) *
                                   glm::rotate(glm::mat4(1), glm::half_pi<float>(), glm::vec3(0, 0, 1)) * size, lo, hi);
  // the floor, lit by both suns (N.L = 0.707 each), at half the walls' albedo: the same W
  s.materials.push_back(Material{.name = "floor", .base_color = glm::vec4(0.25f, 0.25f, 0.25f, 1)});
  s.meshes.push_back(Mesh{"floor square", {Primitive{0, 6, 1}}});
  s.instances.push_back(Instance{"floor", 1, glm::translate(glm::mat4(1), glm::vec3(lo.x, 0, lo.z)) *
                                                 glm::scale(glm::mat4(1), glm::vec3(gap, 1, length)), {}});
  s.lights.push_back(test::directional("sun on the left wall", glm::vec3(-1, -1, 0), 2.f));
  s.lights.push_back(test::directional("sun on the right wall", glm::vec3(1, -1, 0), 2.f));
  return s;
}

TEST(SsgiHardCases, OverlappingSampleDisksSendNoMoreThanTheirEmitters) {
  World w(slot_scene(0.6f, 2.f, 4.f));
  // the albedos as the G-buffer stores them (sRGB8), the walls' L1 half the floor's
  const auto stored = [](float a) { return srgb_to_linear(std::round(linear_to_srgb(a) * 255.f) / 255.f); };
  const float albedo = std::max(stored(0.25f), 0.5f * stored(0.5f));
  double worst = 0;
  for (float x : {0.05f, 0.1f, 0.15f})
    for (float y : {0.8f, 1.1f, 1.5f}) {
      const FrameCamera cam = look(cornell(), glm::vec3(x, y, 1.5f), glm::vec3(-0.02f, 0.f, -1.5f));
      const float most = brightest_emitter(w, cam, albedo);  // W, the same for every emitter
      for (int n : {32, 64}) {
        const ImageF gi = w.frame.indirect(cam, GiMode::Ssgi, {.ao = false, .samples = n, .blur = false});
        ASSERT_TRUE(all_finite(gi));
        EXPECT_GT(largest_rgb(gi), 0.5f * most);  // the walls and the floor light each other
        EXPECT_LE(largest_rgb(gi), most * (1.f + 0x1p-9f)) << "view from " << x << ", " << y << ", " << n << " samples";
        worst = std::max(worst, double(largest_rgb(gi) / most));
      }
    }
  std::cout << "slot: the largest L1_ind is " << worst << " of the emitters' W\n";
}

// [back-faces-test]
// The source's back-face layer, on a case built for it: the Cornell box's back wall alone, and
// 0.5 in front of it a panel 0.6 square (two back-to-back copies of the floor's quad, 1 cm
// apart), a point light between panel and wall. The panel's lit side faces the wall, away from
// the camera: every emitter the camera sees sends the wall nothing (the wall's own pixels lie
// in its plane, cos = 0; the panel's near side is unlit, the light behind it, and faces away
// from the wall anyway), so without the layer the pass finds at most 5 % of the truth's energy
// on the wall (measured: 0). The layer holds the lit side, 1 cm behind the dark one; with it
// the pass must find what the screen-limited truth of both layers shows: nothing hides the lit
// side from the wall, so the whole truth, less what the disk's sample areas miss where emitter
// and receiver meet at grazing angles (the wall beside the panel's edges). Bound: 0.5 .. 1.3 of
// the truth's energy on the wall (measured 0.90 on llvmpipe, relative error 1 -> 0.26), the same band as the
// Cornell box's colour bleeding allows its regions (0.3 .. 1.3), narrowed below because the
// emitter here is a flat panel facing its receiver squarely, the disk transfer's exact case.
World panel_facing_the_wall() {
  Scene scene = cornell().scene;
  int floor_mesh = -1;
  std::vector<Instance> kept;
  for (const Instance& i : scene.instances) {
    if (i.name == "floor") floor_mesh = i.mesh;
    if (i.name == "back_wall") kept.push_back(i);
  }
  // the floor's quad (2 x 2, facing +y) turned to face -z (lit side, toward the wall) and +z
  for (float side : {-1.f, 1.f}) {
    Instance panel{.name = side < 0 ? "panel_lit" : "panel_dark", .mesh = floor_mesh};
    panel.model = glm::translate(glm::mat4(1), glm::vec3(0.f, 1.f, -0.5f + 0.005f * side)) *
                  glm::rotate(glm::mat4(1), side * glm::half_pi<float>(), glm::vec3(1, 0, 0)) *
                  glm::scale(glm::mat4(1), glm::vec3(0.3f, 1.f, 0.3f));
    kept.push_back(panel);
  }
  scene.instances = kept;
  Light light = scene.lights.at(0);
  light.position = glm::vec3(0.f, 1.f, -0.75f);
  light.intensity = 0.25f;
  scene.lights = {light};
  return World(std::move(scene));
}

TEST(SsgiBackFaces, LayerRecoversAnEmitterThatFacesAway) {
  World w = panel_facing_the_wall();
  const FrameCamera cam = w.camera("front");
  const auto names = w.names(cam);
  const ImageF t = truth(w, cam, {.samples = 256});
  GiSettings s{.samples = 64, .pattern = Pattern::Randomised};
  const ImageF off = w.frame.indirect(cam, GiMode::Ssgi, s);
  s.back_faces = true;
  const ImageF on = w.frame.indirect(cam, GiMode::Ssgi, s);
  ASSERT_TRUE(all_finite(on));
  std::vector<std::uint8_t> wall(names.size());
  long n = 0;
  for (std::size_t i = 0; i < names.size(); ++i) n += wall[i] = names[i] == "back_wall";
  ASSERT_GT(n, 1000);
  const GiErrors e_off = gi_errors(off, t, &wall), e_on = gi_errors(on, t, &wall);
  std::cout << "panel facing the wall: truth " << e_on.mean_truth << " on " << n << " wall pixels; captured without the "
            << "layer " << e_off.captured << ", with it " << e_on.captured << " (relative error " << e_off.relative
            << " -> " << e_on.relative << ")\n";
  book_row("08_back_faces_test", {{"case", "panel facing the wall"}},
           {{"truth", e_on.mean_truth}, {"captured_off", e_off.captured}, {"captured_on", e_on.captured},
            {"relative_off", e_off.relative}, {"relative_on", e_on.relative}});
  EXPECT_GT(e_on.mean_truth, 0.01);  // the wall receives light from the panel (well above the noise)
  EXPECT_LT(e_off.captured, 0.05);
  EXPECT_GT(e_on.captured, 0.5);
  EXPECT_LT(e_on.captured, 1.3);
  EXPECT_LT(e_on.relative, e_off.relative);
  // the layer holds the lit side (its light, through the view) and nothing where no back face is
  const ImageRGBA8 view = w.frame.image(cam, GiMode::Ssgi, s, GiShow::BackFaces);
  double lit = 0, elsewhere = 0;
  long n_lit = 0, n_else = 0;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const double v = view.pixels[i * 4 + 0] + view.pixels[i * 4 + 1] + view.pixels[i * 4 + 2];
    if (names[i] == "panel_dark") lit += v, ++n_lit;
    else elsewhere += v, ++n_else;
  }
  EXPECT_GT(lit / double(std::max(n_lit, 1L)), 30.0);  // the lit side's light, in 8-bit steps summed over rgb
  EXPECT_EQ(elsewhere, 0.0);
}
// In the Cornell box the layer adds emitters (the boxes' far sides, the tall box's top) and
// changes nothing where it has none: the sky, and the pass with the layer off is the pass.
TEST(SsgiBackFaces, CornellBoxGainsLittleAndLosesNothing) {
  World& w = cornell();
  const FrameCamera cam = w.camera("front");
  const ImageF t = truth(w, cam);
  GiSettings s{.samples = 64, .pattern = Pattern::Randomised};
  const GiErrors off = gi_errors(w.frame.indirect(cam, GiMode::Ssgi, s), t);
  s.back_faces = true;
  const ImageF on_image = w.frame.indirect(cam, GiMode::Ssgi, s);
  const GiErrors on = gi_errors(on_image, t);
  std::cout << "Cornell box, back-face layer: captured " << off.captured << " -> " << on.captured << ", relative "
            << off.relative << " -> " << on.relative << "\n";
  ASSERT_TRUE(all_finite(on_image));
  EXPECT_GE(on.captured, off.captured);  // the layer only adds emitters
  EXPECT_LT(on.captured, 1.1);           // and invents no light (ConvergesToWhatTheScreenShows' bound)
}
// [/back-faces-test]

// [guard-band-test]
// The guard band with 0 pixels is today's frame, byte for byte: the same frame drawn by chapter
// 03's frame with the stage and no band at all.
TEST(SsgiGuardBand, ZeroBandIsTheFrameWithoutOne) {
  World& w = cornell();
  const FrameCamera cam = w.camera("front");
  GiFrame zero(w.gpu, kW, kH, 0);
  const ImageRGBA8 ours = zero.image(cam, GiMode::Ssgi, {.samples = 32});
  ch03::DeferredFrame plain(w.gpu);
  plain.volumes().set_lights(w.frame.lights());
  GiStage stage(w.gpu);
  plain.add_stage(stage);
  stage.set(GiMode::Ssgi, {.samples = 32}, GiShow::Image, w.scene.ambient);
  OutputTarget target(kW, kH);
  plain.render(cam, {target.framebuffer(), kW, kH});
  EXPECT_EQ(ours.pixels, target.read().pixels);
}
// With a band and no pass that reads other pixels (mode off), the screen's part of the wide
// frame is the screen's frame: the wide camera keeps every pixel centre's ray. Float rounding of
// the two projections may flip a pixel whose centre lies on a triangle's edge or move a value by
// one step: at most 1 step anywhere, and at most 0.5 % of the pixels differing (measured on
// llvmpipe: 2 of 14 400 pixels, by 1 step).
TEST(SsgiGuardBand, ScreensPartOfTheWideFrameIsTheScreen) {
  World& w = cornell();
  const FrameCamera cam = w.camera("front");
  GiFrame banded(w.gpu, kW, kH, 24);
  const ImageRGBA8 a = banded.image(cam, GiMode::Off, {}), b = w.frame.image(cam, GiMode::Off, {});
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  long differ = 0;
  int worst = 0;
  for (std::size_t i = 0; i < a.pixels.size(); i += 4) {
    int d = 0;
    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int(a.pixels[i + c]) - int(b.pixels[i + c])));
    differ += d > 0;
    worst = std::max(worst, d);
  }
  std::cout << "guard band 24 px, mode off: " << differ << " pixels differ, by at most " << worst << "\n";
  book_row("08_guard_band_crop_test", {{"case", "mode off, 24 px"}}, {{"pixels_differ", double(differ)}, {"largest_difference", double(worst)}});
  EXPECT_LE(worst, 1);
  EXPECT_LE(double(differ), 0.005 * kW * kH);
}
// The red wall just off the screen (EmitterEntirelyOffScreenIsLost's camera): without a band the
// pass loses its light; a band of 45 pixels (half the height) on every side brings the wall's lower part into the
// frame, and the pass must find what that wider screen shows: the band-limited truth (the
// screen-limited truth of the wide camera, cropped), whose red bleeding on the floor's left edge
// must be a real part of the truth's (more than 20 %, else the band shows nothing to recover).
// The pass's red there must reach half of the band-limited truth's, the band of
// ColourBleedingHasTheTruthsSignAndMagnitude's lower bound with room for the band's wall being
// seen steeply from above, and stay below 1.3x of it, that test's upper bound (measured on
// llvmpipe: the band-limited truth 0.017, 0.32 of the truth's 0.053; the pass 0.021, 1.24x of
// it, where the disk's samples of the wall seen at a slant stand for areas the slant clamp
// grows; without the band 0).
TEST(SsgiGuardBand, OffScreenEmitterWithinTheBandIsRecovered) {
  World& w = cornell();
  const FrameCamera cam = look(w, glm::vec3(0.4f, 1.9f, 0.2f), glm::vec3(0.4f, 0.f, 0.2f), glm::vec3(0, 0, -1));
  const auto names = w.names(cam);
  constexpr int g = 45;
  GiFrame banded(w.gpu, kW, kH, g);
  const GuardBand band{g};
  const FrameCamera wide = band.widen(cam, kW, kH);
  const ImageF t = truth(w, cam, {.samples = 256});
  const ImageF seen = band.crop(cached_ray_traced_indirect(w.scene, w.frame.lights(), wide, band.width(kW), band.height(kH),
                                                           {.samples = 256, .screen_limited = true}));
  const GiSettings s{.samples = 64, .pattern = Pattern::Randomised};
  const ImageF without = w.frame.indirect(cam, GiMode::Ssgi, s), with = banded.indirect(cam, GiMode::Ssgi, s);
  const double want = red_excess(t, names, "floor", 0, 30), in_band = red_excess(seen, names, "floor", 0, 30);
  const double got0 = red_excess(without, names, "floor", 0, 30), got = red_excess(with, names, "floor", 0, 30);
  std::cout << "red wall in the band: truth " << want << ", band-limited truth " << in_band << ", pass without the band "
            << got0 << ", with it " << got << "\n";
  book_row("08_guard_band_test", {{"case", "red wall in a 45 px band"}},
           {{"truth", want}, {"band_truth", in_band}, {"pass_off", got0}, {"pass_on", got}});
  EXPECT_GT(in_band, 0.2 * want);
  EXPECT_LT(got0, 0.2 * want);
  EXPECT_GT(got, 0.5 * in_band);
  EXPECT_LT(got, 1.3 * in_band);
}
// [/guard-band-test]

TEST(SsgiSettings, BadSettingsSayWhat) {
  World& w = cornell();
  const FrameCamera cam = w.camera("front");
  auto message = [&](const GiSettings& s) {
    try {
      w.frame.indirect(cam, GiMode::Ssgi, s);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({.samples = 0}).find("samples must be between 1 and 128"), std::string::npos);
  EXPECT_NE(message({.gi_radius = -1.f}).find("radii must be positive"), std::string::npos);
  EXPECT_NE(message({.bounces = 3}).find("bounces must be 1 or 2"), std::string::npos);
}

