// Chapter 09 on the GPU (llvmpipe in CI): tiled and clustered culling against chapter 03's
// stencil volumes through the same frame, the exact counts, the lists, and the hard cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <map>
#include <tuple>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/03_light_volumes/light_counts.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/02_gbuffer/layout.h"
#include "chapters/04_neon/capsule.h"
#include "chapters/04_neon/neon_scene.h"
#include "chapters/04_neon/neon_stage.h"
#include "chapters/09_clustered/clustered_forward.h"
#include "chapters/09_clustered/clustered_lights.h"
#include "chapters/09_clustered/density.h"
#include "common/error.h"
#include "common/image.h"
#include "common/metrics.h"
#include "common/paths.h"
#include "common/target.h"
#include "tests/unit/book_data.h"
#include "tests/unit/gl_environment.h"

using namespace lp;
using namespace lp::ch09;
using ch03::Strategy;

namespace {

struct Render {
  ImageRGBA8 image;
  std::vector<float> l1, l2;       // the light buffer, RGBA float
  std::vector<float> heat;         // lights lit per pixel (chapter 03's HeatLit), R
  ch03::FragmentCounts stencil;    // the stencil pass's counts
  EvalCounts counts;               // ours
  ClusterStats stats;
};

std::vector<float> read_rgba(GLuint texture, int w, int h) {
  std::vector<float> v(std::size_t(w) * h * 4);
  glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(v.size() * 4), v.data());
  return v;
}

class World {
 public:
  explicit World(const std::string& scene, const ch02::Layout& layout = ch02::our_layout())
      : scene_(load_scene(from_root(scene))), gpu_(scene_), frame_(gpu_, layout) {}
  Scene scene_;
  SceneGpu gpu_;
  ch03::DeferredFrame frame_;
};

class ClusteredGl : public ::testing::Test {
 protected:
  static void TearDownTestSuite() {  // GL objects go before the context (gl_environment.h)
    delete street_;
    delete atrium_;
    street_ = atrium_ = nullptr;
  }
  static World& street() { return *(street_ ? street_ : street_ = new World("assets/street/street.gltf")); }
  static World& atrium() { return *(atrium_ ? atrium_ : atrium_ = new World("assets/atrium/atrium.gltf")); }

  static FrameCamera camera(World& w, const std::string& view, int width, int height) {
    return frame_camera(w.scene_.camera(view), float(width) / float(height));
  }
  static void set_lights(World& w, int count) {
    w.frame_.volumes().set_lights(ch03::build_light_set(ch03::lights_for_count(w.scene_, count),
                                                        ch03::cut_threshold(1.f, ch03::peak_reflectance(w.scene_)),
                                                        w.frame_.volumes().shapes()));
  }
  // The frame with chapter 03's stencil volumes (pass = nullptr) or with `pass` (or `forward`).
  static Render render(World& w, const FrameCamera& cam, int width, int height, ClusteredLights* pass,
                       bool heat = true, Strategy volumes = Strategy::Stencil, ClusteredForward* forward = nullptr) {
    OutputTarget target(width, height);
    if (forward) pass = &forward->lists();
    w.frame_.set_strategy(volumes);
    if (forward) {
      w.frame_.set_local_lights(forward);
      forward->set_counting(true);
    } else {
      w.frame_.set_local_lights(pass);
      if (pass) pass->set_counting(true);
    }
    w.frame_.volumes().set_counting(true);
    if (pass && pass->settings().floor) {  // the floor's lists grow a frame late: a benchmark settles first
      w.frame_.render(cam, {target.framebuffer(), width, height});
      pass->wait_stats();
    }
    Render r;
    PassMetrics metrics;
    w.frame_.render(cam, {target.framebuffer(), width, height}, &metrics);
    metrics.end_frame();
    metrics.wait_all();
    EXPECT_EQ(metrics.error(), "");
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    r.image = target.read();
    r.l1 = read_rgba(w.frame_.light().diffuse(), width, height);
    r.l2 = read_rgba(w.frame_.light().specular(), width, height);
    if (pass) {
      r.counts = pass->counts();
      r.stats = pass->wait_stats();
    } else {
      r.stencil = w.frame_.volumes().counts();
    }
    if (heat) {
      w.frame_.render(cam, {target.framebuffer(), width, height}, nullptr, {.show = ch03::FrameShow::HeatLit});
      std::vector<float> h = read_rgba(w.frame_.light().diffuse(), width, height);
      for (std::size_t i = 0; i < h.size(); i += 4) r.heat.push_back(h[i]);
    }
    w.frame_.set_local_lights(nullptr);
    return r;
  }

  // ZBinStaged*'s case: lights along the view, each tile size of `tiles` checked (with `shapes`,
  // also the lanes and blocks a shape cannot take, and tiled-staged at 32-pixel tiles).
  static void zbin_staged_cases(const std::vector<int>& tiles, bool shapes);
  // The lanes in the heavy tiles alone (ClusterSettings::lanes_from), against one lane's render
  // and four lanes' in every tile of the same case.
  static void lanes_in_heavy_tiles(World& w, const FrameCamera& cam, int width, int height, const ClusterSettings& one_lane,
                                   const ClusteredLights::ZBinLists& lists, const Render& one, const Render& four);

  static World* street_;
  static World* atrium_;
};
World* ClusteredGl::street_ = nullptr;
World* ClusteredGl::atrium_ = nullptr;

// [tolerance]
// How far our light buffer may be from the stencil volumes'. Both add the same lights (the
// same cut, the same local_light() code) in the same order, light order, starting from the
// same global light. The stencil volumes add each light by blending into RGBA16F: every add
// rounds the running sum to half precision (relative error at most 2^-11). We sum in float
// and round once when we store. With k lights lighting a pixel the two sums differ by at
// most (k + 1) * 2^-11 of the larger of them (each partial sum is at most the final one: the
// terms are not negative), and each light evaluation may differ by float rounding (a few
// 2^-24 relative; nothing next to 2^-11). So, per channel: |ours - stencil| <= (k + 1) *
// 2^-11 * max(ours, stencil) + 2^-24, with k from our heat map of lit lights (our lit pairs
// are exactly the full-screen pass's: LitPairsEqualTheFullScreenPassExactly).
// (Chapter 03's volumes miss nothing that is lit within 99 % of the cut, and our count of lit
// pixel-light pairs is compared with the full-screen count exactly below; what the last 1 %
// of a radius adds is at most the threshold, 1/(255*12.92) ~ 3e-4, so a missed light there
// is allowed by a further threshold x peak reflectance per light: the cut bound.)
struct Tolerance {
  double cut_slack = 0;  // threshold x peak reflectance: what one light beyond 99 % of its cut adds
  double per_light = std::ldexp(1.0, -11);  // relative, per light added (see above)
  bool within(float ours, float theirs, float k_lit) const {
    const double bound = (double(k_lit) + 1.0) * per_light * std::max(std::fabs(ours), std::fabs(theirs)) +
                         std::ldexp(1.0, -24) + cut_slack;
    return std::fabs(double(ours) - double(theirs)) <= bound;
  }
};
// [/tolerance]

struct Diff {
  std::size_t failing = 0;
  double max_abs = 0;
  std::string first;
};
Diff diff(const Render& ours, const Render& theirs, const std::vector<float>& k_lit, const Tolerance& tol) {
  Diff d;
  for (std::size_t i = 0; i < ours.l1.size(); ++i) {
    if (i % 4 == 3) continue;
    const float k = k_lit[i / 4];  // lights lit here, from our heat map: we count every one (LitPairsEqual...)
    for (const auto* pair : {&ours.l1, &ours.l2}) {
      const float a = (*pair)[i], b = (pair == &ours.l1 ? theirs.l1 : theirs.l2)[i];
      d.max_abs = std::max(d.max_abs, std::fabs(double(a) - double(b)));
      if (!tol.within(a, b, k)) {
        if (d.failing++ == 0)
          d.first = "pixel " + std::to_string(i / 4) + (pair == &ours.l1 ? " L1 " : " L2 ") + std::to_string(a) + " vs " +
                    std::to_string(b) + " (" + std::to_string(k) + " lights)";
      }
    }
  }
  return d;
}

// The image, from the light buffers' bound: F = albedo L1 + L2 + emissive has the same
// relative bound e = (k + 1) 2^-11 (its terms are not negative). The sRGB encoding's slope
// times F is at most 1.055 / 2.4 ~ 0.44 on its power segment (0.04 on its linear one), so F
// moves by at most 255 * 0.44 * e steps before rounding; plus one step for the rounding and
// one for chapter 03's own edge allowance (a light beyond 99 % of its cut that the volumes
// missed moves the output by at most one step: test_03_light_volumes_gl.cpp, kSameImage).
std::size_t image_failures(const ImageRGBA8& ours, const ImageRGBA8& theirs, const std::vector<float>& k_lit,
                           std::string& first) {
  std::size_t failing = 0;
  const std::size_t w = std::size_t(ours.width), h = std::size_t(ours.height);
  for (std::size_t i = 0; i < ours.pixels.size(); ++i) {
    if (i % 4 == 3) continue;
    const std::size_t x = (i / 4) % w, y = (i / 4) / w;  // the image's rows run top down, GL's bottom up
    const float k = k_lit[(h - 1 - y) * w + x];
    const double e = (double(k) + 1.0) * std::ldexp(1.0, -11);
    const int allowed = int(std::floor(255.0 * (1.055 / 2.4) * e)) + 2;
    const int d = std::abs(int(ours.pixels[i]) - int(theirs.pixels[i]));
    if (d > allowed && failing++ == 0)
      first = "pixel " + std::to_string(i / 4) + ": " + std::to_string(d) + " steps, allowed " + std::to_string(allowed) +
              " k " + std::to_string(k) + " values " + std::to_string(ours.pixels[i]) + " " + std::to_string(theirs.pixels[i]);
  }
  return failing;
}

Tolerance tolerance_for(const Scene& s) {
  return {double(ch03::cut_threshold(1.f, ch03::peak_reflectance(s))) * double(ch03::peak_reflectance(s))};
}

// The program's modes and the floor benchmark's (zbin-floor: exact per-pixel lists), which
// must give the same image and lit pairs.
std::vector<std::string> every_mode() {
  std::vector<std::string> m = kClusterModes;
  m.insert(m.end(), kBenchModes.begin(), kBenchModes.end());
  return m;
}

// Clusters whose tiles are tiled shading's (16 pixels at 160 x 90), so that the two differ in
// depth only.
ClusterSettings clusters_like_tiles() {
  ClusterSettings fine = settings_for_mode("clustered");
  fine.clusters = {10, 6, 24};
  return fine;
}

}  // namespace

TEST_F(ClusteredGl, TiledAndClusteredEqualTheStencilVolumes) {
  struct Case {
    World* world;
    std::string view;
    int lights;
  };
  const std::vector<Case> cases = {{&street(), "street_level", 0},   {&street(), "street_level", 2000},
                                   {&atrium(), "overview", 0},
                                   {&atrium(), "overview", 600}};
  const int w = 128, h = 72;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.view + " with " + std::to_string(c.lights) + " lights");
    set_lights(*c.world, c.lights);
    const FrameCamera cam = camera(*c.world, c.view, w, h);
    const Render stencil = render(*c.world, cam, w, h, nullptr, false);
    ASSERT_GT(stencil.stencil.lit, 1000u);
    std::vector<float> k;
    for (const std::string& mode : every_mode()) {
      SCOPED_TRACE(mode);
      ClusteredLights pass(c.world->frame_.volumes(), settings_for_mode(mode));
      // Lights lit per pixel: the same in every mode (the same cut, every lit pair listed), so
      // the first mode's heat map serves the others.
      const Render r = render(*c.world, cam, w, h, &pass, k.empty());
      if (k.empty()) k = r.heat;
      const Diff d = diff(r, stencil, k, tolerance_for(c.world->scene_));
      EXPECT_EQ(d.failing, 0u) << d.first << "; largest difference " << d.max_abs;
      EXPECT_EQ(r.stats.cells_over, 0u);
      // Every pixel a light lights is in its cell's list: we light at least what the volumes do.
      EXPECT_GE(r.counts.lit, stencil.stencil.lit_inner);
      EXPECT_GE(r.counts.evaluated, r.counts.lit);
      std::string first;
      EXPECT_EQ(image_failures(r.image, stencil.image, k, first), 0u) << first;
      if (HasFailure()) return;  // one failing mode says it; the rest would only take minutes
    }
  }
}

namespace {
// The street's lights plus `extra` (the directional lights kept).
void set_light_list(World& w, std::vector<Light> lights) {
  w.frame_.volumes().set_lights(ch03::build_light_set(lights, ch03::cut_threshold(1.f, ch03::peak_reflectance(w.scene_)),
                                                      w.frame_.volumes().shapes()));
}
// Each tile's lights: the bits of its masks.
std::vector<std::size_t> lights_per_tile(const ClusteredLights::ZBinLists& z) {
  std::vector<std::size_t> n;
  for (std::size_t t = 0; z.words && (t + 1) * z.words <= z.masks.size(); ++t) {
    n.push_back(0);
    for (std::size_t k = 0; k < z.words; ++k) n.back() += std::size_t(std::popcount(z.masks[t * z.words + k]));
  }
  return n;
}
// Light buffers' channels (L1 and L2) that differ by more than regrouping the same non-negative
// terms can make them, k <= 4 096 terms a pixel: a float sum of k of them in any order is within
// (k - 1) 2^-24 of their exact sum S, two orders within 2k 2^-24 S of each other; both round once
// to half, which may flip one half ulp (at most 2^-10 of the value, 2^-24 below the normals):
// |a - b| <= (2^-11 + 2^-10) max(a, b) + 2^-24 < 2^-9 max + 2^-24. `differ` counts those not equal.
std::size_t beyond_regrouping(const std::vector<float>& l1, const std::vector<float>& l2, const std::vector<float>& m1,
                              const std::vector<float>& m2, std::size_t& differ) {
  std::size_t outside = 0;
  differ = 0;
  for (const auto& [x, y] : {std::pair{&l1, &m1}, std::pair{&l2, &m2}})
    for (std::size_t i = 0; i < x->size() && i < y->size(); ++i) {
      const double u = (*x)[i], v = (*y)[i], bound = std::ldexp(std::max(std::abs(u), std::abs(v)), -9) + std::ldexp(1.0, -24);
      differ += u != v;
      outside += std::abs(u - v) > bound;
    }
  return outside + (l1.size() != m1.size() || l2.size() != m2.size());
}
// The most lights any tile of Z-binning's masks holds (its set bits).
std::size_t most_lights_in_a_tile(const ClusteredLights::ZBinLists& z) {
  const std::vector<std::size_t> n = lights_per_tile(z);
  return n.empty() ? 0 : *std::max_element(n.begin(), n.end());
}
}  // namespace

// Our lit count is exact: every (pixel, light) pair the full-screen pass lights (chapter 03's
// reference: every light at every pixel) is lit by exactly one evaluation from the lists.
TEST_F(ClusteredGl, LitPairsEqualTheFullScreenPassExactly) {
  World& w = street();
  set_lights(w, 0);
  const int width = 96, height = 54;
  const FrameCamera cam = camera(w, "street_level", width, height);
  OutputTarget target(width, height);
  w.frame_.set_strategy(Strategy::FullScreen);
  w.frame_.volumes().set_counting(true);
  w.frame_.render(cam, {target.framebuffer(), width, height});
  const ch03::FragmentCounts full = w.frame_.volumes().counts();
  ASSERT_GT(full.lit, 1000u);
  std::map<std::string, std::uint64_t> evaluated;
  for (const std::string& mode : every_mode()) {
    ClusteredLights pass(w.frame_.volumes(), settings_for_mode(mode));
    const Render r = render(w, cam, width, height, &pass, false);
    EXPECT_EQ(r.counts.lit, full.lit) << mode;
    EXPECT_LT(r.counts.evaluated, full.shaded) << mode << ": culling evaluates fewer than every light everywhere";
    evaluated[mode] = r.counts.evaluated;
  }
  // The floor evaluates only the lights whose cut reaches the surface: fewer than any culling.
  for (const auto& [mode, e] : evaluated)
    if (mode != "zbin-floor") {
      EXPECT_LT(evaluated["zbin-floor"], e) << mode;
    }
  EXPECT_GT(evaluated["zbin-floor"], full.lit) << "lights within their cut that face away light nothing";
}

// A near slice (cluster_grid.h) moves where the slices begin, nothing else: every lit pair is
// still listed, each pixel's list holds its lights in light order, so the sums are the same
// bit for bit. A few metres deep, the slices it frees for the far street evaluate fewer lights;
// 12 m deep it holds the nearest lamps in one slice and evaluates more (the trade-off the grid
// sweep measures).
TEST_F(ClusteredGl, ANearSliceListsEveryLitPairAndChangesNoPixel) {
  World& w = street();
  set_lights(w, 2000);
  const int width = 160, height = 90;
  const FrameCamera cam = camera(w, "street_level", width, height);
  ClusteredLights plain(w.frame_.volumes(), clusters_like_tiles());
  const Render a = render(w, cam, width, height, &plain, false);
  std::map<float, std::uint64_t> evaluated;
  for (const float near_slice : {2.f, 5.f, 12.f}) {
    SCOPED_TRACE("near slice " + std::to_string(near_slice) + " m");
    ClusterSettings s = clusters_like_tiles();
    s.near_slice = near_slice;
    ClusteredLights near(w.frame_.volumes(), s);
    const Render b = render(w, cam, width, height, &near, false);
    ASSERT_TRUE(near.grid().has_near_slice());
    EXPECT_EQ(b.counts.lit, a.counts.lit);
    std::printf("near slice %.0f m: evaluated %llu against %llu without\n", near_slice, (unsigned long long)b.counts.evaluated,
                (unsigned long long)a.counts.evaluated);
    evaluated[near_slice] = b.counts.evaluated;
    EXPECT_EQ(b.stats.cells_over, 0u);
    EXPECT_TRUE(b.l1 == a.l1 && b.l2 == a.l2) << "the light buffers differ";
    EXPECT_TRUE(b.image.pixels == a.image.pixels) << "the images differ";
  }
  EXPECT_LT(evaluated[2.f], a.counts.evaluated);
  EXPECT_LT(evaluated[5.f], a.counts.evaluated);
  EXPECT_GT(evaluated[12.f], evaluated[5.f]);
}

// The subgroup path (shade.glsl's shared-list loop, where the driver has subgroup operations)
// reads a list the whole subgroup shares once, and each invocation adds the same lights in the
// same order as the fallback: the light buffers equal bit for bit, the counts exactly. Tiled
// with 16-pixel tiles, every subgroup shares its list: a subgroup lies within one 8 x 8 work
// group, and those lie within one tile. A driver without subgroups takes the fallback and says so
// (LIGHTPASS_TEST_NO_SUBGROUPS=1 stands for one here).
TEST_F(ClusteredGl, ASharedListReadOnceForTheSubgroupChangesNoPixel) {
  World& w = street();
  set_lights(w, 2000);
  const int width = 160, height = 90;
  const FrameCamera cam = camera(w, "street_level", width, height);
  const std::string support = subgroup_support();
  std::printf("subgroup operations here: %s\n", support.empty() ? "none" : support.c_str());
  for (const std::string mode : {"tiled", "clustered"}) {
    SCOPED_TRACE(mode);
    ClusterSettings off = settings_for_mode(mode);
    off.subgroups = SubgroupUse::Off;
    ClusteredLights fallback(w.frame_.volumes(), off);
    const Render a = render(w, cam, width, height, &fallback, false);
    EXPECT_EQ(fallback.subgroup_path(), "off");
    EXPECT_EQ(a.counts.shared, 0u);
    ASSERT_GT(a.counts.lit, 1000u);
    ClusterSettings any = settings_for_mode(mode);
    any.subgroups = SubgroupUse::Any;
    ::setenv("LIGHTPASS_TEST_NO_SUBGROUPS", "1", 1);
    ClusteredLights without(w.frame_.volumes(), any);
    const Render b = render(w, cam, width, height, &without, false);
    ::unsetenv("LIGHTPASS_TEST_NO_SUBGROUPS");
    EXPECT_EQ(without.subgroup_path(), "none (fallback)");
    EXPECT_EQ(b.counts.shared, 0u);
    EXPECT_TRUE(b.l1 == a.l1 && b.l2 == a.l2);
    // The default uses KHR's subgroups only: ARB's ballot alone (llvmpipe) is slower than the loop.
    ClusteredLights native(w.frame_.volumes(), settings_for_mode(mode));
    render(w, cam, width, height, &native, false);
    EXPECT_EQ(native.subgroup_path(), support == "KHR_shader_subgroup" ? support : "none (fallback)");
    if (support.empty()) continue;  // nothing more to compare on this driver
    ClusteredLights with(w.frame_.volumes(), any);
    const Render c = render(w, cam, width, height, &with, false);
    EXPECT_EQ(with.subgroup_path(), support);
    EXPECT_EQ(c.counts.lit, a.counts.lit);
    EXPECT_EQ(c.counts.evaluated, a.counts.evaluated);
    EXPECT_EQ(c.counts.surface, a.counts.surface);
    EXPECT_TRUE(c.l1 == a.l1 && c.l2 == a.l2) << "the light buffers differ";
    EXPECT_TRUE(c.image.pixels == a.image.pixels) << "the images differ";
    if (mode == "tiled")
      EXPECT_EQ(c.counts.shared, c.counts.surface) << "every subgroup lies in one tile";
    else
      EXPECT_GT(c.counts.shared, 0u) << "no subgroup shared a cluster's list";
    std::printf("%s: %llu of %llu pixels shaded from a shared list\n", mode.c_str(), (unsigned long long)c.counts.shared,
                (unsigned long long)c.counts.surface);
  }
}

// Clusters of different depths in one subgroup (an edge, a step in depth) have different lists:
// with the merged walk (shade.glsl's subgroup-merge) the subgroup walks them together, a light at
// a time, and each invocation still adds its own lights in its list's order, so the light
// buffers equal the fallback's bit for bit and the counts exactly. Every pixel is shaded either
// from a shared list or by the walk, and some by the walk (the street at 160 x 90 has clusters
// of several depths in many 8 x 8 groups).
TEST_F(ClusteredGl, ListsThatDifferWalkedTogetherChangeNoPixel) {
  const std::string support = subgroup_support();
  if (support.empty()) GTEST_SKIP() << "no subgroup operations on this driver";
  World& w = street();
  set_lights(w, 2000);
  const int width = 160, height = 90;
  const FrameCamera cam = camera(w, "street_level", width, height);
  ClusterSettings off = settings_for_mode("clustered");
  off.subgroups = SubgroupUse::Off;
  ClusteredLights fallback(w.frame_.volumes(), off);
  const Render a = render(w, cam, width, height, &fallback, false);
  ASSERT_GT(a.counts.lit, 1000u);
  ClusterSettings merge = settings_for_mode("clustered");
  merge.subgroups = SubgroupUse::Any;
  merge.subgroup_merge = true;
  ClusteredLights walked(w.frame_.volumes(), merge);
  const Render c = render(w, cam, width, height, &walked, false);
  EXPECT_EQ(walked.subgroup_path(), support);
  EXPECT_EQ(c.counts.lit, a.counts.lit);
  EXPECT_EQ(c.counts.evaluated, a.counts.evaluated);
  EXPECT_EQ(c.counts.surface, a.counts.surface);
  EXPECT_TRUE(c.l1 == a.l1 && c.l2 == a.l2) << "the light buffers differ";
  EXPECT_GT(c.counts.merged, 0u) << "no subgroup walked different lists";
  EXPECT_EQ(c.counts.shared + c.counts.merged, c.counts.surface) << "a pixel neither shared a list nor walked";
  std::printf("%llu of %llu pixels from a shared list, %llu by the merged walk\n", (unsigned long long)c.counts.shared,
              (unsigned long long)c.counts.surface, (unsigned long long)c.counts.merged);
}

// The index list is compacted: the cells' lists tile [0, total) without gap or overlap, each
// in ascending light order (the order chapter 03 adds them in), and every entry names a light.
TEST_F(ClusteredGl, ListsAreCompactedAndInLightOrder) {
  World& w = street();
  set_lights(w, 3000);
  const int width = 160, height = 90;
  for (const std::string& mode : {std::string("tiled"), std::string("clustered")}) {
    SCOPED_TRACE(mode);
    ClusteredLights pass(w.frame_.volumes(), settings_for_mode(mode));
    render(w, camera(w, "street_level", width, height), width, height, &pass, false);
    std::vector<glm::uvec2> cells = pass.cell_lists();
    const std::vector<std::uint32_t> list = pass.index_list();
    ASSERT_EQ(list.size(), pass.stats().indices);
    ASSERT_GT(list.size(), 0u);
    std::sort(cells.begin(), cells.end(), [](glm::uvec2 a, glm::uvec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    std::uint64_t next = 0;
    for (const glm::uvec2& c : cells) {
      if (c.y == 0) continue;
      ASSERT_EQ(c.x, next) << "a gap or an overlap in the index list";
      for (std::uint32_t k = 0; k < c.y; ++k) {
        ASSERT_LT(list[c.x + k], w.frame_.volumes().lights().local_count());
        if (k) {
          ASSERT_LT(list[c.x + k - 1], list[c.x + k]) << "not in light order";
        }
      }
      next += c.y;
    }
    EXPECT_EQ(next, list.size());
  }
}

// Over capacity, and no read-back in the frame: the draw whose list does not fit shades its
// full cells from every light (the same light buffer bit for bit: the lights it did not list
// add exactly 0, in the same order; the same lit pairs, more evaluated) and the overflow is
// read a frame late, counted exactly; the next draw's list has grown and fits. With growth off
// every draw overflows, is reported, and still loses no light.
TEST_F(ClusteredGl, AListOverCapacityIsReportedAFrameLateAndLosesNoLight) {
  World& w = street();
  set_lights(w, 0);
  const int width = 160, height = 90;
  const FrameCamera cam = camera(w, "street_level", width, height);
  ClusteredLights roomy(w.frame_.volumes());
  const Render want = render(w, cam, width, height, &roomy, false);
  ASSERT_GT(want.stats.indices, 100u);
  ASSERT_EQ(want.stats.cells_over, 0u);
  ASSERT_EQ(want.stats.regrown, 0);

  ClusterSettings small;
  small.initial_indices = 16;
  ClusteredLights tight(w.frame_.volumes(), small);
  w.frame_.set_local_lights(&tight);
  tight.set_counting(true);
  OutputTarget target(width, height);
  w.frame_.render(cam, {target.framebuffer(), width, height});
  EXPECT_EQ(tight.stats().frame, 0u) << "the draw read its lists' state back: a stall";
  const ClusterStats first = tight.wait_stats();
  EXPECT_EQ(first.frame, 1u);
  EXPECT_GT(first.cells_over, 0u);
  EXPECT_EQ(first.regrown, 0) << "grown before an overflow was read";
  EXPECT_EQ(first.indices, want.stats.indices) << "what the cells asked for, exactly";
  EXPECT_GT(first.over_entries, 0u);
  EXPECT_EQ(read_rgba(w.frame_.light().diffuse(), width, height), want.l1);
  EXPECT_EQ(read_rgba(w.frame_.light().specular(), width, height), want.l2);
  const EvalCounts first_counts = tight.counts();
  EXPECT_EQ(first_counts.lit, want.counts.lit);
  EXPECT_GT(first_counts.evaluated, want.counts.evaluated);
  w.frame_.set_local_lights(nullptr);
  const Render grown = render(w, cam, width, height, &tight, false);  // draw 2: grown from draw 1's state
  EXPECT_EQ(grown.stats.regrown, 1);
  EXPECT_EQ(grown.stats.cells_over, 0u);
  EXPECT_GE(grown.stats.capacity, want.stats.indices);
  EXPECT_EQ(grown.l1, want.l1);
  EXPECT_EQ(grown.counts.lit, want.counts.lit);
  EXPECT_EQ(grown.counts.evaluated, want.counts.evaluated);

  small.grow = false;
  ClusteredLights fixed(w.frame_.volumes(), small);
  for (int draw = 0; draw < 2; ++draw) {
    const Render r = render(w, cam, width, height, &fixed, false);
    EXPECT_EQ(r.stats.regrown, 0);
    EXPECT_GT(r.stats.cells_over, 0u);
    // What the full cells asked for plus what the others stored is every entry the roomy list holds.
    std::uint64_t stored = 0;
    for (const glm::uvec2& c : fixed.cell_lists())
      if (c.x != 0xFFFFFFFFu) stored += c.y;
    EXPECT_LE(stored, 16u);
    EXPECT_EQ(r.stats.over_entries + stored, want.stats.indices);
    EXPECT_EQ(r.l1, want.l1);
    EXPECT_EQ(r.counts.lit, want.counts.lit);
  }
}

// zbin-floor's exact lists, built a tile at a time by zbin_staged.comp (FLOOR_LISTS: a walk
// that counts, a prefix sum and an atomic a tile, a walk that writes). Whether one invocation
// a pixel walks the span, four in every tile, or four in the heavy tiles alone (lanes_from),
// each pixel's list holds the same lights; the lists tile the index list without gap or
// overlap; with one lane each is in sorted order. Over capacity a tile's pixels are shaded
// through Z-binning (no light lost) and counted a frame late.
TEST_F(ClusteredGl, TheFloorsExactListsAreTheSameWithAnyLanes) {
  World& w = street();
  set_lights(w, 3000);
  const int width = 160, height = 90;
  const FrameCamera cam = camera(w, "street_level", width, height);
  const std::uint32_t lights = w.frame_.volumes().lights().local_count();
  ClusterSettings one = settings_for_mode("zbin-floor");
  one.pixel_lanes = 1;
  ClusteredLights first(w.frame_.volumes(), one);
  const Render want = render(w, cam, width, height, &first, false);
  ASSERT_EQ(want.stats.cells_over, 0u);
  ASSERT_GT(want.counts.lit, 10000u);
  const ClusteredLights::ZBinLists zbin = first.zbin_lists();
  std::vector<std::uint32_t> position(zbin.order.size());
  for (std::size_t p = 0; p < zbin.order.size(); ++p) position[zbin.order[p]] = std::uint32_t(p);
  std::vector<std::size_t> per_tile = lights_per_tile(zbin);
  std::erase(per_tile, 0u);
  ASSERT_GT(per_tile.size(), 4u);
  std::nth_element(per_tile.begin(), per_tile.begin() + std::ptrdiff_t(per_tile.size() / 2), per_tile.end());
  const int median = int(per_tile[per_tile.size() / 2]);

  // Each pixel's lights, sorted; checking on the way that the lists are compacted.
  auto lists_of = [&](ClusteredLights& pass, bool in_sorted_order) {
    std::vector<glm::uvec2> cells = pass.cell_lists();
    const std::vector<std::uint32_t> index = pass.index_list();
    EXPECT_EQ(cells.size(), std::size_t(width) * std::size_t(height));
    EXPECT_EQ(index.size(), pass.stats().indices);
    std::vector<std::vector<std::uint32_t>> pixels;
    for (const glm::uvec2& c : cells) {
      std::vector<std::uint32_t> l;
      for (std::uint32_t k = 0; k < c.y && c.x + k < index.size(); ++k) {
        EXPECT_LT(index[c.x + k], lights);
        if (in_sorted_order && k > 0) {
          EXPECT_LT(position[index[c.x + k - 1]], position[index[c.x + k]]) << "not in sorted order";
        }
        l.push_back(index[c.x + k]);
      }
      std::sort(l.begin(), l.end());
      pixels.push_back(l);
    }
    std::sort(cells.begin(), cells.end(), [](glm::uvec2 a, glm::uvec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    std::uint64_t next = 0;
    for (const glm::uvec2& c : cells) {
      if (c.y == 0) continue;
      EXPECT_EQ(c.x, next) << "a gap or an overlap in the index list";
      next = c.x + std::uint64_t(c.y);
    }
    EXPECT_EQ(next, index.size());
    return pixels;
  };
  const std::vector<std::vector<std::uint32_t>> exact = lists_of(first, true);
  if (HasFailure()) return;
  struct Case {
    int lanes, from;
  };
  for (const Case c : {Case{4, 0}, Case{2, 0}, Case{4, median}}) {
    SCOPED_TRACE(std::to_string(c.lanes) + " lanes from " + std::to_string(c.from) + " lights");
    ClusterSettings s = settings_for_mode("zbin-floor");
    s.pixel_lanes = c.lanes;
    s.lanes_from = c.from;
    ClusteredLights laned(w.frame_.volumes(), s);
    const Render r = render(w, cam, width, height, &laned, false);
    EXPECT_EQ(r.counts.lit, want.counts.lit);
    EXPECT_EQ(r.counts.evaluated, want.counts.evaluated);
    std::size_t differ = 0;
    const std::vector<std::vector<std::uint32_t>> got = lists_of(laned, false);
    for (std::size_t i = 0; i < exact.size() && i < got.size(); ++i) differ += got[i] != exact[i];
    EXPECT_EQ(differ, 0u) << "pixels whose list holds other lights than one lane's";
    if (c.from > 0) {
      const ClusteredLights::LaneTiles t = laned.lane_tiles();
      EXPECT_FALSE(t.heavy.empty());
      EXPECT_FALSE(t.light.empty());
    }
  }

  // Over capacity: the tiles that do not fit are shaded through Z-binning, the same lights in
  // sorted order, those beyond their cut adding exactly 0. The order inside a sort bucket is the
  // atomics', so two passes may sort alike (the same light buffers, bit for bit) or not (the same
  // terms regrouped: within beyond_regrouping's bound, each pixel's k at most its list's length).
  ClusterSettings small = one;
  small.initial_indices = 16;
  small.grow = false;
  ClusteredLights tight(w.frame_.volumes(), small);
  const Render r = render(w, cam, width, height, &tight, false);
  EXPECT_GT(r.stats.cells_over, 0u);
  EXPECT_EQ(r.stats.indices, want.stats.indices) << "what the pixels asked for, exactly";
  EXPECT_EQ(r.counts.lit, want.counts.lit);
  EXPECT_GT(r.counts.evaluated, want.counts.evaluated);
  ASSERT_LE(want.stats.max_list, 4096u) << "the regrouping bound assumes at most 4 096 lights a pixel";
  std::size_t differ = 0;
  EXPECT_EQ(beyond_regrouping(r.l1, r.l2, want.l1, want.l2, differ), 0u) << "channels beyond the regrouping's bound";
  if (tight.zbin_lists().order == zbin.order) {
    EXPECT_EQ(differ, 0u) << "sorted alike, and the light buffers differ";
  }
  std::uint64_t stored = 0, over = 0;
  for (const glm::uvec2& c : tight.cell_lists()) {
    if (c.x == 0xFFFFFFFFu) ++over;
    else stored += c.y;
  }
  EXPECT_LE(stored, 16u);
  EXPECT_EQ(over, r.stats.cells_over);
  EXPECT_EQ(r.stats.over_entries + stored, want.stats.indices);
}

TEST_F(ClusteredGl, ZeroLightsAddNothing) {
  World& w = street();
  std::vector<Light> none;
  for (const Light& l : w.scene_.lights)
    if (l.type == LightType::Directional) none.push_back(l);
  set_light_list(w, none);
  const int width = 64, height = 36;
  const FrameCamera cam = camera(w, "street_level", width, height);
  const Render stencil = render(w, cam, width, height, nullptr, false);
  for (const std::string& mode : every_mode()) {
    ClusteredLights pass(w.frame_.volumes(), settings_for_mode(mode));
    const Render r = render(w, cam, width, height, &pass, false);
    EXPECT_EQ(r.counts.evaluated, 0u) << mode;
    // The density's denominator is every surface pixel, lit or not (the street fills most of the view).
    EXPECT_GT(r.counts.surface, std::uint64_t(width * height / 2)) << mode;
    EXPECT_LT(r.counts.surface, std::uint64_t(width * height)) << mode << ": the sky is no surface";
    EXPECT_EQ(r.stats.indices, 0u) << mode;
    EXPECT_EQ(r.l1, stencil.l1) << mode << ": the global light alone, untouched";
    EXPECT_EQ(r.l2, stencil.l2) << mode;
  }
}

namespace {
// One cross-check of all four modes against the stencil volumes on a given light list.
void expect_all_modes_equal_stencil(World& w, const FrameCamera& cam, int width, int height,
                                    Render (*render)(World&, const FrameCamera&, int, int, ClusteredLights*, bool, Strategy,
                                                     ClusteredForward*),
                                    std::vector<Render>* out = nullptr) {
  const Render stencil = render(w, cam, width, height, nullptr, false, Strategy::Stencil, nullptr);
  std::vector<float> k;
  for (const std::string& mode : every_mode()) {
    SCOPED_TRACE(mode);
    ClusteredLights pass(w.frame_.volumes(), settings_for_mode(mode));
    const Render r = render(w, cam, width, height, &pass, k.empty(), Strategy::Stencil, nullptr);
    if (k.empty()) k = r.heat;  // lights lit per pixel, the same in every mode
    const Diff d = diff(r, stencil, k, tolerance_for(w.scene_));
    EXPECT_EQ(d.failing, 0u) << d.first << "; largest difference " << d.max_abs;
    EXPECT_GE(r.counts.lit, stencil.stencil.lit_inner);
    EXPECT_EQ(r.stats.cells_over, 0u);
    if (out) out->push_back(r);
  }
}
}  // namespace

// One light whose cut sphere holds the camera and everything it sees: every cell lists it,
// every surface pixel evaluates it once.
TEST_F(ClusteredGl, ALightCoveringTheWholeScreen) {
  World& w = street();
  const int width = 64, height = 36;
  const FrameCamera cam = camera(w, "street_level", width, height);
  Light big;
  big.name = "big";
  big.position = cam.position;
  big.intensity = 5000;
  set_light_list(w, {big});
  ASSERT_GT(w.frame_.volumes().lights().points[0].position_radius.w, 500.f);
  std::vector<Render> rs;
  expect_all_modes_equal_stencil(w, cam, width, height, &ClusteredGl::render, &rs);
  std::uint64_t surface = 0;  // pixels the light lights (its heat map is 1 there)
  for (float k : rs[0].heat) surface += k > 0 ? 1 : 0;
  ASSERT_GT(surface, std::uint64_t(width * height / 2));
  for (const Render& r : rs) EXPECT_EQ(r.counts.evaluated, r.counts.lit);
  for (const Render& r : rs) EXPECT_EQ(r.counts.lit, surface);
  // One light evaluated at every surface pixel: the pass's count of surface pixels (the
  // density's denominator) is the evaluated count.
  for (const Render& r : rs) EXPECT_EQ(r.counts.surface, r.counts.evaluated);
}

// An off-centre frustum (a shifted lens, or chapter 11's jitter writ large): P[2][0] and P[2][1]
// move every cell's box sideways by d * offset / focal at view depth d. Shifted by a third and a
// quarter of the screen, a box built as if the frustum were centred misses lights at the
// screen's far side by whole tiles, so the lists must use the offsets to equal the volumes.
TEST_F(ClusteredGl, AnOffCentreFrustumListsWhatTheVolumesLight) {
  World& w = street();
  const int width = 64, height = 36;
  FrameCamera cam = camera(w, "street_level", width, height);
  cam.projection[2][0] = 0.65f;
  cam.projection[2][1] = -0.5f;
  set_lights(w, 1000);
  expect_all_modes_equal_stencil(w, cam, width, height, &ClusteredGl::render);
}

// The camera inside many lights (chapter 03's hardest case for front faces): 200 lights
// around the eye, each reaching past it.
TEST_F(ClusteredGl, CameraInsideManyLights) {
  World& w = street();
  const int width = 96, height = 54;
  const FrameCamera cam = camera(w, "street_level", width, height);
  std::vector<Light> lights;
  for (int i = 0; i < 200; ++i) {
    Light l;
    l.name = "around " + std::to_string(i);
    const float a = float(i) * 2.39996f;
    l.position = cam.position + glm::vec3(std::cos(a), 0.3f * std::sin(3.f * a), std::sin(a)) * (0.2f + 0.01f * float(i));
    l.color = glm::vec3(0.5f + 0.5f * std::cos(a), 0.6f, 0.5f + 0.5f * std::sin(a));
    l.intensity = 2.f;
    lights.push_back(l);
  }
  set_light_list(w, lights);
  int inside = 0;
  for (const auto& p : w.frame_.volumes().lights().points)
    inside += glm::distance(glm::vec3(p.position_radius), cam.position) < p.position_radius.w;
  ASSERT_EQ(inside, 200);
  expect_all_modes_equal_stencil(w, cam, width, height, &ClusteredGl::render);
}

// A depth discontinuity inside a tile: tiled shading's weakness. A lamp post in front of the
// far street gives tiles whose depth range spans both; the lights between are evaluated for
// pixels they cannot reach. Counted: tiled evaluates more per lit pixel than clustered does on
// the same view, and both still give the stencil image.
TEST_F(ClusteredGl, DepthDiscontinuityInATileCostsTiledExtraEvaluations) {
  World& w = street();
  set_lights(w, 2000);
  const int width = 160, height = 90;
  const FrameCamera cam = camera(w, "street_level", width, height);
  ClusteredLights tiled(w.frame_.volumes(), settings_for_mode("tiled"));
  ClusteredLights clustered(w.frame_.volumes(), clusters_like_tiles());
  const Render t = render(w, cam, width, height, &tiled, false);
  const Render c = render(w, cam, width, height, &clustered, false);
  EXPECT_EQ(t.counts.lit, c.counts.lit);
  EXPECT_GT(t.counts.evaluated, c.counts.evaluated + c.counts.evaluated / 4)
      << "tiled " << t.counts.evaluated_per_lit() << " per lit, clustered " << c.counts.evaluated_per_lit();
}

// Harada's 2.5D depth mask is tiled shading's fix for the case above. It can only drop a light
// whose depth extent falls between a tile's surfaces. Measured on two light sets: the street's
// 2000 lamps (cut at their glTF range, 4.5 to 8 m, as long as the gaps), and the same lamps
// at a quarter of their range (1 to 2 m, most of them floating between the surfaces). The
// mask must keep every lit pair (the same lit count, and the stencil volumes' image within
// the cross-check's tolerance), never add work, and drop some lights from the lists; how many
// is the book's measurement (09_depth_mask.csv), not a bound: on a street seen at 160 x 90 a
// tile's surfaces fill most of its 32 bins.
TEST_F(ClusteredGl, TheDepthMaskDropsLightsInATilesDepthGaps) {
  World& w = street();
  const int width = 160, height = 90;
  const FrameCamera cam = camera(w, "street_level", width, height);
  for (const float scale : {1.f, 1.f / 4.f}) {
    std::vector<Light> lights = ch03::lights_for_count(w.scene_, 2000);
    for (Light& l : lights)
      if (l.type != LightType::Directional) l.range *= scale;
    set_light_list(w, lights);
    const std::string name = scale == 1.f ? "lamps" : "range/4";
    SCOPED_TRACE(name);
    ClusteredLights tiled(w.frame_.volumes(), settings_for_mode("tiled"));
    ClusteredLights masked(w.frame_.volumes(), settings_for_mode("tiled-2.5d"));
    ClusteredLights clustered(w.frame_.volumes(), clusters_like_tiles());
    const Render t = render(w, cam, width, height, &tiled, false);
    const Render m = render(w, cam, width, height, &masked, true);
    const Render c = render(w, cam, width, height, &clustered, false);
    const Render stencil = render(w, cam, width, height, nullptr, false);
    ASSERT_GT(m.counts.lit, 5000u);
    EXPECT_EQ(m.counts.lit, t.counts.lit) << "a lit pair lost or added";
    const Diff d = diff(m, stencil, m.heat, tolerance_for(w.scene_));
    EXPECT_EQ(d.failing, 0u) << d.first;
    EXPECT_LT(m.stats.indices, t.stats.indices) << "the mask dropped no light from any tile";
    EXPECT_LT(m.counts.evaluated, t.counts.evaluated);
    // Every tile's masked list is a sub-list of its unmasked one (the same order: light order).
    const std::vector<glm::uvec2> tl = tiled.cell_lists(), ml = masked.cell_lists();
    const std::vector<std::uint32_t> ti = tiled.index_list(), mi = masked.index_list();
    ASSERT_EQ(tl.size(), ml.size());
    std::size_t not_sub = 0;
    for (std::size_t k = 0; k < tl.size(); ++k) {
      const auto tb = ti.begin() + tl[k].x, mb = mi.begin() + ml[k].x;
      if (!std::includes(tb, tb + tl[k].y, mb, mb + ml[k].y)) ++not_sub;
    }
    EXPECT_EQ(not_sub, 0u);
    for (const auto& [mode, e] : {std::pair{"tiled", t.counts}, {"tiled-2.5d", m.counts}, {"clustered", c.counts}})
      lp::test::book_row("09_depth_mask", {{"lights", name}, {"mode", mode}},
                         {{"evaluated", double(e.evaluated)}, {"lit", double(e.lit)}, {"evaluated_per_lit", e.evaluated_per_lit()}});
    lp::test::book_row("09_depth_mask_lists", {{"lights", name}},
                       {{"tiled_entries", double(t.stats.indices)}, {"masked_entries", double(m.stats.indices)}});
  }
}

// Z-binning's lists, read back and checked against the CPU: the order is every light once,
// by view depth (within one of the sort's buckets); each bin's range holds every light whose
// depth extent reaches the bin and ends at lights that reach it (tight); each tile's bits are
// within tiled shading's list of that tile (the same sphere-box test on the same bounds) and
// hold every light of it whose screen rectangle (cluster_grid.h's sphere_tiles, the C++ twin,
// on a sphere 1 % smaller, for rounding) holds the tile: a tile's box is the box around its frustum, wider than the tile, so
// tiled keeps lights there that cannot cover one of its pixels. On the street's lamps at a
// quarter of their range, small next to the street, and at full range.
TEST_F(ClusteredGl, ZBinRangesAndTileBitsHoldExactlyTheLightsThatReach) {
  World& w = street();
  const int width = 160, height = 90;
  const FrameCamera cam = camera(w, "street_level", width, height);
  // The bins' step has two paths (zbin.comp): a work group's bins in shared memory when they
  // span at most 1 024 bins (always with the default 1 024), one atomic per light and bin when
  // wider (16 384 bins: the groups of lights nearest the eye span thousands). The tiles' too: a
  // light's own invocation walks a rectangle of at most 16 tiles, a work group a larger one,
  // its 256 invocations striding when there are more tiles than that (4-pixel tiles: 920).
  struct Case {
    float scale;
    int bins, tile_px;
  };
  for (const Case& k : {Case{1.f, 1024, 16}, Case{1.f / 4.f, 1024, 16}, Case{1.f, 16384, 16}, Case{1.f, 1024, 4}}) {
    SCOPED_TRACE("range x " + std::to_string(k.scale) + ", " + std::to_string(k.bins) + " bins, tiles of " +
                 std::to_string(k.tile_px) + " px");
    std::vector<Light> lights = ch03::lights_for_count(w.scene_, 2000);
    for (Light& l : lights)
      if (l.type != LightType::Directional) l.range *= k.scale;
    set_light_list(w, lights);
    ClusterSettings tiles = settings_for_mode("tiled"), binned = settings_for_mode("zbin");
    tiles.tile_px = binned.tile_px = k.tile_px;
    binned.zbins = k.bins;
    ClusteredLights tiled(w.frame_.volumes(), tiles);
    ClusteredLights zbin(w.frame_.volumes(), binned);
    const Render t = render(w, cam, width, height, &tiled, false);
    const Render z = render(w, cam, width, height, &zbin, false);
    EXPECT_EQ(z.counts.lit, t.counts.lit);
    const ClusteredLights::ZBinLists lists = zbin.zbin_lists();
    // The lights' view-space centres and cuts, in the light order the GPU holds them.
    const ch03::LightSet& set = w.frame_.volumes().lights();
    std::vector<glm::vec4> spheres;
    for (const auto& p : set.points) spheres.push_back(p.position_radius);
    for (const auto* spots : {&set.cones, &set.wide_spots})
      for (const auto& sp : *spots) spheres.push_back(sp.position_radius);
    const std::size_t n = spheres.size();
    ASSERT_GT(n, 1000u);
    ASSERT_EQ(lists.order.size(), n);
    std::vector<std::uint32_t> position(n, 0xFFFFFFFFu);
    for (std::size_t p = 0; p < n; ++p) {
      ASSERT_LT(lists.order[p], n);
      ASSERT_EQ(position[lists.order[p]], 0xFFFFFFFFu) << "light " << lists.order[p] << " sorted twice";
      position[lists.order[p]] = std::uint32_t(p);
    }
    auto depth = [&](std::size_t i) { return -(cam.view * glm::vec4(glm::vec3(spheres[i]), 1.f)).z; };
    const float bucket = std::pow(cam.zfar / cam.znear, 1.f / 16384.f) * (1.f + 1e-5f);  // zbin.comp's keys
    for (std::size_t p = 1; p < n; ++p) {
      const float a = std::max(depth(lists.order[p - 1]), cam.znear), b = std::max(depth(lists.order[p]), cam.znear);
      ASSERT_LE(a, b * bucket) << "sorted positions " << p - 1 << " and " << p << " out of depth order";
    }
    // The bins: the C++ twin of zbin_of is slice_of on a grid of that many slices.
    const int bins = zbin.settings().zbins;
    ASSERT_EQ(lists.ranges.size(), std::size_t(bins));
    const Grid g = grid_of_tiles(width, height, k.tile_px, bins, cam.znear, cam.zfar);
    std::size_t missing = 0, loose = 0, used = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const float d = depth(i), r = spheres[i].w;
      if (d + r < cam.znear || d - r > cam.zfar) continue;
      for (int b = slice_of(g, d - r); b <= slice_of(g, d + r); ++b)
        if (lists.ranges[b].x > position[i] || position[i] > lists.ranges[b].y) ++missing;
    }
    for (int b = 0; b < bins; ++b) {
      const glm::uvec2 range = lists.ranges[std::size_t(b)];
      if (range.x > range.y) continue;
      ++used;
      // Each end is a light that reaches the bin (its extent, a little wider than the GPU's padding).
      for (const std::uint32_t p : {range.x, range.y}) {
        ASSERT_LT(p, n);
        const float d = depth(lists.order[p]), r = spheres[lists.order[p]].w * 1.001f + 1e-3f;
        if (slice_of(g, (d - r) * 0.999f) > b || slice_of(g, (d + r) * 1.001f) < b) ++loose;
      }
    }
    EXPECT_EQ(missing, 0u) << "(light, bin) pairs whose bin's range leaves the light out";
    EXPECT_EQ(loose, 0u) << "range ends that are lights not reaching the bin";
    EXPECT_GT(used, std::size_t(bins / 20));
    // The tiles: the same lights as tiled's lists, tile by tile.
    const std::vector<glm::uvec2> cells = tiled.cell_lists();
    const std::vector<std::uint32_t> index = tiled.index_list();
    ASSERT_EQ(lists.masks.size(), cells.size() * lists.words);
    std::size_t tiles_differ = 0, entries = 0, skipped = 0;
    std::string first;
    for (std::size_t tile = 0; tile < cells.size(); ++tile) {
      std::vector<std::uint32_t> want(index.begin() + cells[tile].x, index.begin() + cells[tile].x + cells[tile].y), got;
      for (std::size_t k = 0; k < lists.words; ++k)
        for (int bit = 0; bit < 32; ++bit)
          if (lists.masks[tile * lists.words + k] >> bit & 1u) got.push_back(lists.order[k * 32 + std::size_t(bit)]);
      std::sort(got.begin(), got.end());
      entries += got.size();
      std::vector<std::uint32_t> kept;  // tiled's, less the lights whose rectangle misses the tile
      const int tx = int(tile) % g.tiles_x, ty = int(tile) / g.tiles_x;
      for (const std::uint32_t i : want) {
        const glm::vec3 c(cam.view * glm::vec4(glm::vec3(spheres[i]), 1.f));
        if (sphere_tiles(cam, g, c, spheres[i].w * 0.99f).holds(tx, ty)) kept.push_back(i);  // must be kept
        if (!sphere_tiles(cam, g, c, spheres[i].w * 1.01f).holds(tx, ty)) ++skipped;            // may go
      }
      if (!std::includes(want.begin(), want.end(), got.begin(), got.end()) || !std::includes(got.begin(), got.end(), kept.begin(), kept.end()))
        if (tiles_differ++ == 0)
          first = "tile " + std::to_string(tile) + ": " + std::to_string(got.size()) + " bits, tiled lists " +
                  std::to_string(want.size()) + ", of which the rectangles hold " + std::to_string(kept.size());
    }
    EXPECT_EQ(tiles_differ, 0u) << first;
    EXPECT_GT(skipped, 0u) << "no light's rectangle missed a tile its box reached";
    EXPECT_EQ(entries, z.stats.indices) << "the (tile, light) pairs the stats report";
    EXPECT_GT(entries, 1000u);
    // What Z-binning is for: fewer evaluated than tiled for the same lit pairs.
    EXPECT_LT(z.counts.evaluated, t.counts.evaluated);
  }
}

// ClusterSettings::sorted_records: the sort copies each light's record and cone to its sorted
// position, and the shading reads them there. Every copy must be the record of the light the
// order names there (a spot with its cone, a point with none), and the image the unsorted
// pass's: the same lit pairs, and where both sorted alike (the order inside a sort bucket is
// the atomics'), the same light buffers to the bit.
TEST_F(ClusteredGl, ZBinningsSortedRecordsAreTheLightsItsOrderNames) {
  World& w = street();
  set_lights(w, 2000);
  const int width = 160, height = 90;
  const FrameCamera cam = camera(w, "street_level", width, height);
  ClusterSettings indexed = settings_for_mode("zbin"), copied = settings_for_mode("zbin");
  indexed.sorted_records = false;
  copied.sorted_records = true;
  ClusteredLights plain(w.frame_.volumes(), indexed);
  ClusteredLights sorted(w.frame_.volumes(), copied);
  const Render a = render(w, cam, width, height, &plain, false);
  const Render b = render(w, cam, width, height, &sorted, false);
  ASSERT_GT(a.counts.lit, 1000u);
  EXPECT_EQ(b.counts.lit, a.counts.lit);
  const ClusterRecords packed = pack_cluster_lights(w.frame_.volumes().lights());
  ASSERT_GT(packed.first_spot, 0);
  ASSERT_LT(packed.first_spot, int(packed.lights.size())) << "no spot: the cones go untested";
  const ClusteredLights::ZBinLists z = sorted.zbin_lists();
  ASSERT_EQ(z.order.size(), packed.lights.size());
  ASSERT_EQ(z.records.size(), 3 * packed.lights.size());
  std::size_t wrong = 0;
  for (std::size_t p = 0; p < z.order.size(); ++p) {
    const std::uint32_t i = z.order[p];
    ASSERT_LT(i, packed.lights.size());
    const glm::vec4 cone = int(i) >= packed.first_spot ? packed.spots[i - std::size_t(packed.first_spot)].axis_offset : glm::vec4(0.f);
    if (z.records[3 * p] != packed.lights[i].position_radius || z.records[3 * p + 1] != packed.lights[i].radiance_inv_range2 ||
        z.records[3 * p + 2] != cone)
      ++wrong;
  }
  EXPECT_EQ(wrong, 0u) << "sorted positions whose record is not the light the order names";
  const bool alike = z.order == plain.zbin_lists().order;
  std::printf("the two passes sorted %s\n", alike ? "alike: their light buffers compared" : "differently");
  if (alike) {
    EXPECT_EQ(b.counts.evaluated, a.counts.evaluated);
    EXPECT_TRUE(b.l1 == a.l1 && b.l2 == a.l2) << "the light buffers differ";
  }
}

// Four lanes only in the tiles whose masks hold at least lanes_from lights: zbin_lanes.comp
// lists each tile as heavy or light by its count, and the two dispatches shade the heavy with
// four lanes, the light with one. The threshold is the case's median count, so that both lists
// hold tiles. Each list must be exactly the tiles on its side of it (the masks counted here), and
// each pixel must be, bit for bit, what one lane (light tiles) or four lanes in every tile
// (heavy) made of it: a tile shaded twice, by the wrong dispatch or not at all differs there
// (the case's two renders differ in both kinds of tile: checked).
void ClusteredGl::lanes_in_heavy_tiles(World& w, const FrameCamera& cam, int width, int height, const ClusterSettings& one_lane,
                                       const ClusteredLights::ZBinLists& lists, const Render& one, const Render& four) {
  const std::vector<std::size_t> per_tile = lights_per_tile(lists);
  std::vector<std::size_t> sorted = per_tile;
  std::sort(sorted.begin(), sorted.end());
  ASSERT_FALSE(sorted.empty());
  const std::size_t from = std::max<std::size_t>(sorted[sorted.size() / 2], 1);
  ClusterSettings adaptive = one_lane;
  adaptive.pixel_lanes = 4;
  adaptive.lanes_from = int(from);
  ClusteredLights pass(w.frame_.volumes(), adaptive);
  const Render r = render(w, cam, width, height, &pass, false);
  EXPECT_EQ(r.counts.lit, one.counts.lit);
  EXPECT_EQ(r.counts.evaluated, one.counts.evaluated);
  ASSERT_EQ(pass.zbin_lists().order, lists.order) << "the case's sort keys are distinct";
  std::vector<std::uint32_t> heavy, light;
  for (std::size_t t = 0; t < per_tile.size(); ++t) (per_tile[t] >= from ? heavy : light).push_back(std::uint32_t(t));
  ASSERT_FALSE(heavy.empty());
  ASSERT_FALSE(light.empty());
  const ClusteredLights::LaneTiles listed = pass.lane_tiles();
  EXPECT_EQ(listed.heavy, heavy) << "the tiles given four lanes (from " << from << " lights)";
  EXPECT_EQ(listed.light, light) << "the tiles given one lane";
  const int tile = adaptive.tile_px, tiles_x = (width + tile - 1) / tile;
  std::size_t wrong[2] = {0, 0}, apart[2] = {0, 0};  // [light, heavy]: pixels not as their dispatch makes them; where one and four lanes differ
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t t = std::size_t((y / tile) * tiles_x + x / tile), i = (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4;
      const bool is_heavy = per_tile[t] >= from;
      const Render& want = is_heavy ? four : one;
      bool same = true, differ = false;
      for (int c = 0; c < 4; ++c) {
        same = same && r.l1[i + c] == want.l1[i + c] && r.l2[i + c] == want.l2[i + c];
        differ = differ || one.l1[i + c] != four.l1[i + c] || one.l2[i + c] != four.l2[i + c];
      }
      wrong[is_heavy] += !same;
      apart[is_heavy] += differ;
    }
  EXPECT_EQ(wrong[1], 0u) << "pixels of heavy tiles that are not four lanes' sums";
  EXPECT_EQ(wrong[0], 0u) << "pixels of light tiles that are not one lane's sums";
  EXPECT_GT(apart[1], 0u) << "one and four lanes agree in every heavy tile: the case cannot tell them apart";
  EXPECT_GT(apart[0], 0u) << "one and four lanes agree in every light tile: the case cannot tell them apart";
  std::printf("lanes from %zu lights: %zu heavy tiles, %zu light; pixels where one and four lanes differ: %zu, %zu\n", from,
              heavy.size(), light.size(), apart[1], apart[0]);
}

// Z-binning staged (zbin_staged.comp): a work group per tile stages the lights of the span its
// pixels' bins name, in sorted order and in chunks of a group's size, and each pixel adds the
// part of each chunk in its own bin's range. It must add exactly zbin_visit's lights in
// zbin_visit's order: the same evaluated pairs and light buffers, bit for bit. Two passes sort
// alike only where no two lights share a sort key (ties are ordered by the atomics), so the
// case lays its lights out along the view, each 1.3 sort keys deeper than the last (their
// depths grow by a constant ratio, the keys are exponential), spots among them. The hard cases
// are the tiles of near and far surfaces (spans of many bins, each pixel a part of them) and
// spans of more lights than a chunk: the near tiles see over a thousand. ZBinStagedAtOtherTileSizes
// takes the other shapes: 32-pixel tiles, whose 1 024 invocations stage a chunk of 256 (for
// both staged passes); 8; 12, whose chunk of 144 is no power of two for the searches; 1, whose
// walk takes the span 32 sorted positions a round, so that spans cross rounds.
void ClusteredGl::zbin_staged_cases(const std::vector<int>& tiles, bool shapes) {
  World& w = street();
  const int width = 160, height = 90;
  const FrameCamera cam = camera(w, "street_level", width, height);
  const glm::mat4 to_world = glm::inverse(cam.view);
  const glm::vec3 eye = cam.position, forward = -glm::vec3(to_world[2]), right = glm::vec3(to_world[0]),
                  up = glm::vec3(to_world[1]);
  constexpr double kSortKeys = 16384.0;  // zbin.comp's
  const double key_ratio = std::exp(std::log(double(cam.zfar) / double(cam.znear)) / kSortKeys);
  const int n = 3000;
  const double near = 2.0, far = 100.0, ratio = std::exp(std::log(far / near) / double(n - 1));
  ASSERT_GT(std::log(ratio), 1.3 * std::log(key_ratio)) << "lights closer in depth than a sort key";
  std::vector<Light> lights = ch03::lights_for_count(w.scene_, n);
  int local = 0, spots = 0;
  for (Light& l : lights) {
    if (l.type == LightType::Directional) continue;
    const int k = local++;
    const float d = float(near * std::pow(ratio, double(k)));
    l.position = eye + d * forward + float((k * 7) % 11 - 5) * 0.6f * right + (float(k % 5) * 0.5f - 1.2f) * up;
    spots += l.type == LightType::Spot;
  }
  ASSERT_EQ(local, n);
  ASSERT_GT(spots, 0) << "no spot: the staged cones go untested";
  set_light_list(w, lights);
  // 32-pixel tiles too (a group of 1 024 invocations stages 256 records at a time, four
  // invocations test a light's 32 blocks), and 8 (a tile of two blocks).
  for (const int tile : tiles) {
    SCOPED_TRACE("tiles of " + std::to_string(tile) + " px");
    ClusterSettings zbin = settings_for_mode("zbin"), zbin_staged = settings_for_mode("zbin-staged");
    zbin.tile_px = zbin_staged.tile_px = tile;
    zbin_staged.sub_blocks = false;
    zbin_staged.pixel_lanes = 1;  // one invocation a pixel adds zbin_visit's lights in its order (the lanes: below)
    ClusteredLights p(w.frame_.volumes(), zbin);
    ClusteredLights q(w.frame_.volumes(), zbin_staged);
    const Render a = render(w, cam, width, height, &p, false);
    const Render b = render(w, cam, width, height, &q, false);
    ASSERT_EQ(p.zbin_lists().order, q.zbin_lists().order) << "the case's sort keys are distinct";
    ASSERT_GT(a.counts.lit, 200000u) << "the case needs tens of lights a pixel";
    EXPECT_EQ(b.counts.lit, a.counts.lit);
    EXPECT_EQ(b.counts.evaluated, a.counts.evaluated);
    EXPECT_TRUE(b.l1 == a.l1 && b.l2 == a.l2) << "the light buffers differ";
    // The blocks pass over only lights that add nothing to the pixel: the same sums, bit for
    // bit, the same lit pairs, fewer evaluated (and never fewer than the lit). (Blocks of 8 x 4
    // pixels do not tile a 12-pixel tile: refused, below.)
    if (tile % 8 == 0) {
      ClusterSettings blocks = zbin_staged;
      blocks.sub_blocks = true;
      ClusteredLights r(w.frame_.volumes(), blocks);
      const Render c = render(w, cam, width, height, &r, false);
      ASSERT_EQ(p.zbin_lists().order, r.zbin_lists().order);
      EXPECT_EQ(c.counts.lit, a.counts.lit);
      EXPECT_TRUE(c.l1 == a.l1 && c.l2 == a.l2) << "the light buffers differ with the blocks";
      EXPECT_LT(c.counts.evaluated, a.counts.evaluated) << "the blocks pass over no light";
      EXPECT_GE(c.counts.evaluated, c.counts.lit);
      std::printf("tiles of %d px: evaluated %llu, with the blocks %llu, lit %llu\n", tile,
                  (unsigned long long)a.counts.evaluated, (unsigned long long)c.counts.evaluated,
                  (unsigned long long)a.counts.lit);
    }
    // Two and four invocations a pixel (ClusterSettings::pixel_lanes): the same lights evaluated
    // and lit, exactly; the sums regrouped, each a light's non-negative radiance: within
    // beyond_regrouping's bound for k <= 4 096 lights a pixel.
    // (At 16- and 8-pixel tiles, the shapes the blocks take too: 12 and 1 run one lane.)
    const bool lanes_here = tile <= 16 && tile % 8 == 0;
    const std::size_t most = lanes_here ? most_lights_in_a_tile(q.zbin_lists()) : 0;  // bounds a pixel's k
    if (lanes_here) {
      ASSERT_LE(most, 4096u) << "the bound below assumes at most 4 096 lights a pixel";
      Render four;  // four lanes in every tile
      for (const int lanes : {2, 4}) {
        ClusterSettings laned = zbin_staged;
        laned.pixel_lanes = lanes;
        laned.lanes_from = 0;  // every tile
        ClusteredLights laned_pass(w.frame_.volumes(), laned);
        const Render e = render(w, cam, width, height, &laned_pass, false);
        if (lanes == 4) four = e;
        EXPECT_EQ(e.counts.lit, a.counts.lit) << lanes << " lanes";
        EXPECT_EQ(e.counts.evaluated, a.counts.evaluated) << lanes << " lanes";
        std::size_t differ = 0;
        const std::size_t outside = beyond_regrouping(e.l1, e.l2, a.l1, a.l2, differ);
        EXPECT_EQ(outside, 0u) << lanes << " lanes: channels beyond the regrouping's bound (of " << differ << " that differ)";
        std::printf("tiles of %d px, %d lanes: %zu channels differ from one lane's, within the bound\n", tile, lanes, differ);
      }
      lanes_in_heavy_tiles(w, cam, width, height, zbin_staged, q.zbin_lists(), a, four);
    }
    if (tile != 16) continue;
    // Two layouts of the same records, each zbin's evaluations and light buffers again: read
    // through the index (sorted_records off), and staged as a structure of arrays (staged_fields).
    ClusterSettings indexed = zbin_staged, fields = zbin_staged;
    indexed.sorted_records = false;
    fields.staged_fields = true;
    for (ClusterSettings* v : {&indexed, &fields}) {
      ClusterSettings& variant = *v;
      variant.sub_blocks = false;
      ClusteredLights staged_variant(w.frame_.volumes(), variant);
      const Render d = render(w, cam, width, height, &staged_variant, false);
      EXPECT_EQ(d.counts.evaluated, a.counts.evaluated);
      EXPECT_TRUE(d.l1 == a.l1 && d.l2 == a.l2)
          << "the light buffers differ (" << (variant.staged_fields ? "the records' fields staged apart" : "records by index") << ")";
    }
    // The phase clocks (a benchmark's, ClusterSettings::phase_clocks): the same buffers, every
    // phase of the pass timed, the blocks' tests ("reach") only with the blocks, and the sums
    // zeroed once taken.
    for (const bool blocks : {false, true}) {
      ClusterSettings clocked = zbin_staged;
      clocked.phase_clocks = true;
      clocked.sub_blocks = blocks;
      ClusteredLights clocked_pass(w.frame_.volumes(), clocked);
      const Render e = render(w, cam, width, height, &clocked_pass, false);
      EXPECT_TRUE(e.l1 == a.l1 && e.l2 == a.l2) << "the light buffers differ with the phase clocks";
      const std::vector<std::uint64_t> cycles = clocked_pass.take_phase_cycles();
      ASSERT_EQ(cycles.size(), ClusteredLights::phase_names().size());
      for (std::size_t k = 0; k < cycles.size(); ++k) {
        const std::string& phase = ClusteredLights::phase_names()[k];
        if (phase == "reach" && !blocks)
          EXPECT_EQ(cycles[k], 0u) << "the blocks' phase timed without the blocks";
        else
          EXPECT_GT(cycles[k], 0u) << "phase '" << phase << "' not timed" << (blocks ? " (with the blocks)" : "");
      }
      std::printf("phase cycles%s:", blocks ? " with the blocks" : "");
      for (std::size_t k = 0; k < cycles.size(); ++k)
        std::printf(" %s %llu", ClusteredLights::phase_names()[k].c_str(), (unsigned long long)cycles[k]);
      std::printf("\n");
      EXPECT_EQ(clocked_pass.take_phase_cycles(), std::vector<std::uint64_t>(cycles.size(), 0)) << "the sums were not zeroed";
    }
    // A tile with more lights than a chunk holds (so that the chunks are tested).
    EXPECT_GT(most, 4u * 256u) << "no tile holds several chunks of lights";
    std::printf("the most lights in a tile %zu\n", most);
  }
  if (!shapes) return;
  // Shapes the pass cannot take, refused with the reason, not a link error or a wrong image:
  // sub-blocks in a 12-pixel tile, three lanes, lanes in 32-pixel tiles, lanes with sub-blocks,
  // lanes from a negative count of lights.
  for (const auto& [tile, lanes, blocks, from, reason] :
       {std::tuple{12, 1, true, 0, "sub-blocks"}, std::tuple{16, 3, false, 0, "invocations a pixel"},
        std::tuple{32, 2, false, 0, "invocations a pixel"}, std::tuple{16, 4, true, 0, "invocations a pixel"},
        std::tuple{16, 4, false, -1, "lanes_from is a count of lights, not -1"}}) {
    ClusterSettings bad = settings_for_mode("zbin-staged");
    bad.tile_px = tile;
    bad.pixel_lanes = lanes;
    bad.sub_blocks = blocks;
    bad.lanes_from = from;
    ClusteredLights refused(w.frame_.volumes(), bad);
    try {
      render(w, cam, width, height, &refused, false);
      ADD_FAILURE() << lanes << " lane(s) in " << tile << "-pixel tiles" << (blocks ? " with sub-blocks" : "") << " from "
                    << from << " lights not refused";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
    }
    w.frame_.set_local_lights(nullptr);  // (the refused pass goes out of scope)
  }
  // tiled-staged at 32-pixel tiles (its chunks too): tiled's lights in tiled's order.
  {
    ClusterSettings tiled = settings_for_mode("tiled"), tiled_staged = settings_for_mode("tiled-staged");
    tiled.tile_px = tiled_staged.tile_px = 32;
    ClusteredLights p(w.frame_.volumes(), tiled);
    ClusteredLights q(w.frame_.volumes(), tiled_staged);
    const Render a = render(w, cam, width, height, &p, false);
    const Render b = render(w, cam, width, height, &q, false);
    EXPECT_EQ(b.counts.lit, a.counts.lit);
    EXPECT_EQ(b.counts.evaluated, a.counts.evaluated);
    EXPECT_TRUE(b.l1 == a.l1 && b.l2 == a.l2) << "tiled-staged's light buffers differ from tiled's at 32-pixel tiles";
  }
}
TEST_F(ClusteredGl, ZBinStagedAddsZBinningsLightsInItsOrder) { zbin_staged_cases({16}, false); }
TEST_F(ClusteredGl, ZBinStagedAtOtherTileSizes) { zbin_staged_cases({32, 8, 12, 1}, true); }

// Z-binning clears only the mask words the last frame set (tile_words names them; the whole
// masks only when their layout changes). The hard case is a pass kept from frame to frame: its
// lists must be a fresh pass's, tile by tile (as sets of lights: the order inside a sort bucket
// is the atomics'), after a frame with more bits (the lights at full range, then at a quarter,
// from another view: the same layout, the sparse clear) and after a change of layout (fewer
// lights). A bit left from the last frame shows as a light a fresh pass does not list, and
// tile_words must name exactly the words that have bits (the shading skips the others).
TEST_F(ClusteredGl, ZBinningKeptAcrossFramesListsWhatAFreshPassLists) {
  World& w = street();
  const int width = 160, height = 90;
  const std::vector<Camera> views = ch09::views_along(w.scene_.camera("street_level"), 2, 12.f);
  const FrameCamera near_view = frame_camera(views[0], float(width) / float(height));
  const FrameCamera far_view = frame_camera(views[1], float(width) / float(height));
  auto lights_at = [&](int count, float scale) {
    std::vector<Light> lights = ch03::lights_for_count(w.scene_, count);
    for (Light& l : lights)
      if (l.type != LightType::Directional) l.range *= scale;
    set_light_list(w, lights);
  };
  // Each tile's lights (ids, sorted) from the masks and the order; and the tile_words check.
  auto tile_sets = [](const ClusteredLights::ZBinLists& z, std::size_t tiles, std::size_t* misnamed) {
    std::vector<std::vector<std::uint32_t>> sets(tiles);
    const std::size_t word_words = (z.words + 31) / 32;
    EXPECT_EQ(z.masks.size(), tiles * z.words);
    EXPECT_EQ(z.touched.size(), std::max<std::size_t>(tiles * word_words, 1));
    for (std::size_t t = 0; t < tiles; ++t)
      for (std::size_t k = 0; k < z.words; ++k) {
        const std::uint32_t m = z.masks[t * z.words + k];
        const bool named = (z.touched[t * word_words + k / 32] >> (k % 32) & 1u) != 0;
        if (named != (m != 0)) ++*misnamed;
        for (int bit = 0; bit < 32; ++bit)
          if (m >> bit & 1u) sets[t].push_back(z.order[k * 32 + std::size_t(bit)]);
      }
    for (auto& v : sets) std::sort(v.begin(), v.end());
    return sets;
  };
  ClusteredLights kept(w.frame_.volumes(), settings_for_mode("zbin"));
  struct Step {
    int lights;
    float scale;
    const FrameCamera* cam;
    const char* what;
  };
  const Step steps[] = {{2000, 1.f, &near_view, "full range"},
                        {2000, 0.25f, &far_view, "a quarter of the range, another view: the sparse clear"},
                        {2000, 0.25f, &near_view, "back to the first view"},
                        {700, 0.5f, &near_view, "fewer lights: a new layout, cleared whole"}};
  std::size_t first_bits = 0;
  for (const Step& step : steps) {
    SCOPED_TRACE(step.what);
    lights_at(step.lights, step.scale);
    const Render k = render(w, *step.cam, width, height, &kept, false);
    ClusteredLights fresh(w.frame_.volumes(), settings_for_mode("zbin"));
    const Render f = render(w, *step.cam, width, height, &fresh, false);
    const std::size_t tiles = std::size_t(kept.grid().tiles_x) * std::size_t(kept.grid().tiles_y);
    std::size_t misnamed_kept = 0, misnamed_fresh = 0;
    const auto a = tile_sets(kept.zbin_lists(), tiles, &misnamed_kept);
    const auto b = tile_sets(fresh.zbin_lists(), tiles, &misnamed_fresh);
    std::size_t differ = 0, bits = 0;
    for (std::size_t t = 0; t < tiles; ++t) {
      differ += a[t] != b[t];
      bits += a[t].size();
    }
    EXPECT_EQ(differ, 0u) << "tiles whose kept lists are not a fresh pass's";
    EXPECT_EQ(misnamed_kept, 0u) << "mask words tile_words names wrongly (kept pass)";
    EXPECT_EQ(misnamed_fresh, 0u) << "mask words tile_words names wrongly (fresh pass)";
    // Lights in the same depth key land in the sort's scatter in the order its atomics give, so
    // two passes may order ties differently: the lights a pixel evaluates (its bin's index
    // range) are then not the same count, though every tile holds the same lights. Equal
    // orders must evaluate equally.
    if (kept.zbin_lists().order == fresh.zbin_lists().order) { EXPECT_EQ(k.counts.evaluated, f.counts.evaluated); }
    EXPECT_EQ(k.counts.lit, f.counts.lit);
    EXPECT_GT(bits, 100u);
    if (first_bits == 0) first_bits = bits;
    else if (step.scale < 1.f && step.lights == 2000) {
      EXPECT_LT(bits * 2, first_bits) << "the case needs the earlier frame to have set more bits";
    }
  }
}

// 100 000 lights at a small size (16x9): correctness, not time. Every light reaches the GPU,
// and every (pixel, light) pair that lights is lit exactly once: the lit-pair count is an
// integer equal to chapter 03's full-screen pass's (every light at every pixel, no culling),
// so dropping any one light from any one cell fails here, where an image bound cannot see it
// (with thousands of lights a pixel, half-float rounding allows more than one light's share).
// The light is also what that pass gives, within the cross-check's tolerance.
TEST_F(ClusteredGl, HundredThousandLightsAtASmallSize) {
  World& w = street();
  set_lights(w, 100000);
  ASSERT_EQ(w.frame_.volumes().lights().local_count(), 100000u);
  const int width = 16, height = 9;  // every pixel evaluates tens of thousands of lights
  const FrameCamera cam = camera(w, "street_level", width, height);
  const Render full = render(w, cam, width, height, nullptr, false, Strategy::FullScreen);
  ASSERT_EQ(full.stencil.shaded, 100000u * width * height) << "the full-screen pass shades every light everywhere";
  ASSERT_GT(full.stencil.lit, 100000u) << "thousands of lights at each of the 144 pixels";
  std::vector<float> k;
  for (const std::string& mode : {std::string("tiled"), std::string("clustered"), std::string("zbin"), std::string("zbin-staged")}) {
    SCOPED_TRACE(mode);
    ClusterSettings settings = settings_for_mode(mode);
    settings.tile_px = 8;  // tiled and zbin: 2 x 2 tiles
    ClusteredLights pass(w.frame_.volumes(), settings);
    const Render r = render(w, cam, width, height, &pass, k.empty());
    if (k.empty()) k = r.heat;  // lights lit per pixel, the same in both modes
    EXPECT_EQ(r.counts.lit, full.stencil.lit) << "lit (pixel, light) pairs, exactly";
    const Diff d = diff(r, full, k, tolerance_for(w.scene_));
    EXPECT_EQ(d.failing, 0u) << d.first << " indices " << r.stats.indices << " max " << r.stats.max_list
                             << " cap " << r.stats.capacity << " regrown " << r.stats.regrown << " over " << r.stats.cells_over;
    EXPECT_EQ(r.stats.cells_over, 0u);
  }
}

// Clustered forward as the frame's local-light pass (the program's --mode clustered-forward):
// the scene drawn again, each fragment lit from its cluster's list and added into the light
// buffer, then chapter 03's composite. With the float G-buffer (what the stencil volumes read
// is the forward fragment's surface up to renormalising the normal) its light buffer equals
// the volumes' within the cross-check's tolerance plus the normal's share: each of the k
// lights may differ by a relative 2^-20 (test_09_clustered_forward_gl.cpp derives it), so
// per light 2^-11 + 2^-20. The image is held as every mode's: a pass that left the G-buffer's
// textures unbound, or lit some surfaces twice, fails here.
TEST_F(ClusteredGl, ClusteredForwardInTheFrameEqualsTheStencilVolumes) {
  World w("assets/street/street.gltf", ch02::float_layout());
  set_lights(w, 1000);
  const int width = 128, height = 72;
  const FrameCamera cam = camera(w, "street_level", width, height);
  const Render stencil = render(w, cam, width, height, nullptr, false);
  ClusteredForward forward(w.frame_, w.gpu_);
  const Render f = render(w, cam, width, height, nullptr, true, Strategy::Stencil, &forward);
  ClusteredLights deferred(w.frame_.volumes(), settings_for_mode("clustered"));
  const Render d = render(w, cam, width, height, &deferred, false);
  Tolerance tol = tolerance_for(w.scene_);
  tol.per_light = std::ldexp(1.0, -11) + std::ldexp(1.0, -20);
  const Diff diffs = diff(f, stencil, f.heat, tol);
  EXPECT_EQ(diffs.failing, 0u) << diffs.first << "; largest difference " << diffs.max_abs;
  std::string first;
  EXPECT_EQ(image_failures(f.image, stencil.image, f.heat, first), 0u) << first;
  // Each pixel's nearest surface shaded once from its cluster: the deferred pass's counts.
  EXPECT_EQ(f.counts.evaluated, d.counts.evaluated);
  EXPECT_EQ(f.counts.lit, d.counts.lit);
  EXPECT_GE(f.counts.lit, stencil.stencil.lit_inner);
  EXPECT_EQ(f.stats.cells, 16 * 9 * 24);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  w.frame_.set_local_lights(nullptr);
}

// [tubes]
namespace {
// Chapter 04's tubes in chapter 03's frame: the shop street (its lamps, its tubes, its glass),
// the tubes drawn by chapter 04's NeonStage, whose capsule volumes add their light unless the
// clusters do (set_light_by_volumes(false): then only the glass of the tubes is drawn).
struct TubeWorld {
  World world{"assets/street_shop/street_shop.gltf"};
  ch04::NeonTubes tubes;
  ch04::NeonStage neon;
  std::vector<ch04::NeonLight> lights;
  TubeWorld() : neon(world.gpu_, tubes) { world.frame_.add_stage(neon); }
  void upload(std::vector<ch04::NeonLight> l, float threshold) {
    lights = std::move(l);
    tubes.upload(lights, threshold);
  }
};

// The street's tubes cut where chapter 04 cuts them (40 m and more: the whole view), or much
// nearer (a few metres, so that the cut's edge is in the view), with one long tube added that
// runs from beside the camera far down the view: it crosses tiles and slices.
std::vector<ch04::NeonLight> street_tubes_and_a_long_one(const Scene& scene, const FrameCamera& cam) {
  std::vector<ch04::NeonLight> t = ch04::neon_lights(scene);
  const glm::mat4 eye = glm::inverse(cam.view);
  const glm::vec3 right(eye[0]), up(eye[1]), forward(-glm::vec3(eye[2]));
  ch04::NeonLight long_tube;
  long_tube.name = "across the view";
  long_tube.start = cam.position + 3.f * forward + 1.5f * right - 0.8f * up;
  long_tube.end = cam.position + 30.f * forward - 2.5f * right + 1.f * up;
  long_tube.door_axis = glm::normalize(glm::cross(long_tube.end - long_tube.start, right));
  long_tube.color = glm::vec3(0.2f, 0.6f, 1.f);
  long_tube.intensity = t.empty() ? 5.f : t[0].intensity * 4.f;
  t.push_back(long_tube);
  return t;
}
}  // namespace

// The tubes shaded in chapter 09's pass (ClusteredLights::set_tubes) against chapter 04's
// capsule volumes, in the same frame after the same clustered lamps. Both evaluate chapter 04's
// neon_light() on the same G-buffer pixels, and both cut at the same volume radius: the mask is
// inside neon_light(), and the capsule mesh and the cells (capsule_meets_box) only have to hold
// it. So the lit (pixel, tube) pairs are equal exactly, and the light differs by rounding alone:
// the volumes add each tube by blending into RGBA16F (a rounding of the running sum, by
// at most a unit in the last place, 2^-10 relative: GL does not make a conversion to half round
// to nearest, and llvmpipe's blending rounds toward zero, the volumes' light never above the
// clusters') per tube that adds anything, after the lamps' pass stored its sum (one more); the
// clusters sum lamps and tubes in float and store once. With k_t tubes lighting a pixel the two
// differ by at most (k_t + 2) 2^-10 of the larger (every partial sum is at most the final one):
// chapter 09's Tolerance with k = k_t + 1 at 2^-10 a rounding, no cut slack (the same lists
// light the lamps in both). The image, through the composite and sRGB: image_failures' bound.
const Tolerance kAUlpPerRounding{.cut_slack = 0, .per_light = std::ldexp(1.0, -10)};
TEST_F(ClusteredGl, TubesInTheClustersEqualTheirCapsuleVolumes) {
  TubeWorld t;
  const int width = 96, height = 54;
  const FrameCamera cam = camera(t.world, "shops", width, height);
  set_lights(t.world, 0);
  const std::vector<ch04::NeonLight> tubes = street_tubes_and_a_long_one(t.world.scene_, cam);
  ASSERT_GE(tubes.size(), 3u);
  // A threshold that cuts the first tube 2 m away: the others a few metres around that.
  const float near_cut = ch04::max_irradiance_at(tubes[0], 2.f);
  for (const float threshold : {ch04::kNeonCut, near_cut}) {
    t.upload(tubes, threshold);
    for (const ch04::NeonGpu& g : t.tubes.packed()) {
      const float r = ch04::unpack_neon(g).volume_radius;
      if (threshold == ch04::kNeonCut) {
        ASSERT_GT(r, 20.f) << "chapter 04's cut reaches over the view";
      } else {
        ASSERT_LT(r, 12.f) << "the near cut ends in the view";
      }
    }
    for (const std::string& mode : {std::string("clustered"), std::string("tiled")}) {
      SCOPED_TRACE(mode + (threshold == ch04::kNeonCut ? ", chapter 04's cut" : ", a near cut"));
      // The volumes: the lamps from the clusters, then each tube's capsule.
      ClusteredLights lamps(t.world.frame_.volumes(), settings_for_mode(mode));
      t.neon.set_light_by_volumes(true);
      t.neon.volumes().set_counting(true);
      const Render volumes = render(t.world, cam, width, height, &lamps, false);
      const std::uint64_t tube_pairs = t.neon.volumes().counts().lit;
      t.neon.volumes().set_counting(false);
      // The clusters: the lamps and the tubes in one pass; the capsules draw no light.
      t.neon.set_light_by_volumes(false);
      ClusteredLights both(t.world.frame_.volumes(), settings_for_mode(mode));
      both.set_tubes(t.tubes.packed(), t.neon.how());
      const Render clusters = render(t.world, cam, width, height, &both, true);
      const Render lamps_alone = render(t.world, cam, width, height, &lamps, true);
      t.neon.set_light_by_volumes(true);
      ASSERT_GT(tube_pairs, std::uint64_t(width * height / 10)) << "the tubes light a tenth of the view";
      EXPECT_EQ(clusters.counts.lit, volumes.counts.lit + tube_pairs) << "lit (pixel, tube) pairs, exactly";
      EXPECT_EQ(clusters.stats.cells_over, 0u);
      std::vector<float> k(clusters.heat.size());
      for (std::size_t i = 0; i < k.size(); ++i) k[i] = clusters.heat[i] - lamps_alone.heat[i] + 1.f;  // k_t + 1
      // Below half's smallest normal (2^-14) a rounding errs by its subnormal step, 2^-24,
      // however small the value: a step per rounding, at the most roundings any pixel has.
      Tolerance tol = kAUlpPerRounding;
      tol.cut_slack = (double(*std::max_element(k.begin(), k.end())) + 1.0) * std::ldexp(1.0, -24);
      const Diff d = diff(clusters, volumes, k, tol);
      EXPECT_EQ(d.failing, 0u) << d.first << "; largest difference " << d.max_abs;
      std::string first;
      EXPECT_EQ(image_failures(clusters.image, volumes.image, k, first), 0u) << first;
      // Not the same image by accident: without the tubes it differs.
      EXPECT_GT(diff(lamps_alone, volumes, k, tol).failing, std::size_t(width * height / 10));
    }
  }
  t.world.frame_.set_local_lights(nullptr);
}

// The lists on the GPU against the CPU's twin: every cell of the clustered grid (all_cells: a
// list for each) holds each tube whose capsule, 1 % thinner, meets the cell's box on the CPU
// (cluster_box, capsule_meets_box), and none whose capsule 1 % thicker misses it (the 1 % for
// the two sides' rounding). Tubes cut a few metres out, one of them long: each crosses many
// cells, and a tube dropped from any one of them fails here, wherever its light would fall.
TEST_F(ClusteredGl, ATubeWhoseCapsuleCrossesCellsIsNeverDropped) {
  TubeWorld t;
  const int width = 128, height = 72;
  const FrameCamera cam = camera(t.world, "shops", width, height);
  set_lights(t.world, 0);
  const std::vector<ch04::NeonLight> tubes = street_tubes_and_a_long_one(t.world.scene_, cam);
  t.upload(tubes, ch04::max_irradiance_at(tubes[0], 2.f));
  t.neon.set_light_by_volumes(false);
  ClusterSettings settings = settings_for_mode("clustered");
  settings.all_cells = true;
  ClusteredLights pass(t.world.frame_.volumes(), settings);
  pass.set_tubes(t.tubes.packed(), t.neon.how());
  render(t.world, cam, width, height, &pass, false);
  t.neon.set_light_by_volumes(true);
  const std::vector<glm::uvec2> cells = pass.cell_lists();
  const std::vector<std::uint32_t> index = pass.index_list();
  const Grid& g = pass.grid();
  const std::uint32_t first_tube = std::uint32_t(t.world.frame_.volumes().lights().local_count());
  ASSERT_EQ(cells.size(), std::size_t(g.cells()));
  std::size_t dropped = 0, extra = 0, pairs = 0;
  std::vector<std::size_t> cells_of(tubes.size(), 0);
  std::string first;
  for (int slice = 0; slice < g.slices; ++slice)
    for (int ty = 0; ty < g.tiles_y; ++ty)
      for (int tx = 0; tx < g.tiles_x; ++tx) {
        const std::size_t cell = (std::size_t(slice) * g.tiles_y + ty) * g.tiles_x + tx;
        const Box box = cluster_box(cam, g, tx, ty, slice);
        std::vector<bool> listed(tubes.size(), false);
        for (std::uint32_t k = 0; k < cells[cell].y; ++k) {
          const std::uint32_t i = index[cells[cell].x + k];
          if (i >= first_tube) listed[i - first_tube] = true;
        }
        for (std::size_t i = 0; i < tubes.size(); ++i) {
          const ch04::UnpackedNeon u = ch04::unpack_neon(t.tubes.packed()[i]);
          const glm::vec3 a(cam.view * glm::vec4(u.light.start, 1.f)), b(cam.view * glm::vec4(u.light.end, 1.f));
          const bool must = capsule_meets_box(a, b, u.volume_radius * 0.99f, box);
          const bool may = capsule_meets_box(a, b, u.volume_radius * 1.01f, box);
          pairs += must;
          cells_of[i] += listed[i];
          if ((must && !listed[i]) || (listed[i] && !may)) {
            (must ? dropped : extra) += 1;
            if (first.empty())
              first = "tube " + std::to_string(i) + " in cell " + std::to_string(tx) + "," + std::to_string(ty) + "," +
                      std::to_string(slice) + (must ? ": dropped" : ": listed where its capsule misses");
          }
        }
      }
  EXPECT_EQ(dropped, 0u) << first;
  EXPECT_EQ(extra, 0u) << first;
  EXPECT_GT(pairs, 100u);
  for (std::size_t i = 0; i < tubes.size(); ++i) EXPECT_GT(cells_of[i], 1u) << "tube " << i << " crosses cells";
  EXPECT_GT(cells_of.back(), std::size_t(g.slices)) << "the long tube crosses many slices' cells";
  t.world.frame_.set_local_lights(nullptr);
}

// Z-binning sorts and bins spheres: a frame with tubes in it is refused by name, not drawn wrong.
TEST_F(ClusteredGl, ZBinningRefusesTubesByName) {
  TubeWorld t;
  const int width = 32, height = 18;
  const FrameCamera cam = camera(t.world, "shops", width, height);
  set_lights(t.world, 0);
  t.upload(ch04::neon_lights(t.world.scene_), ch04::kNeonCut);
  ClusteredLights pass(t.world.frame_.volumes(), settings_for_mode("zbin"));
  pass.set_tubes(t.tubes.packed());
  t.world.frame_.set_local_lights(&pass);
  OutputTarget target(width, height);
  try {
    t.world.frame_.render(cam, {target.framebuffer(), width, height});
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("Z-binning bins spheres, not chapter 04's tubes"), std::string::npos) << e.what();
  }
  t.world.frame_.set_local_lights(nullptr);
  while (glGetError() != GL_NO_ERROR) {
  }
}
// [/tubes]
