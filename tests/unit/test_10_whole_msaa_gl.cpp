// Chapter 10's whole frame with MSAA (--msaa N): the frame the program draws, against a
// supersampled truth of itself (the same frame at 4x the width and height, box-downsampled in
// linear display light), on the street with its shop windows. The stages without MSAA yet are
// switched off in both, so the two differ only in how a pixel's area is sampled.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "chapters/10_frame/whole_frame.h"
#include "common/error.h"
#include "common/image.h"
#include "common/paths.h"
#include "common/target.h"
#include "tests/unit/gl_environment.h"

using namespace lp;
using namespace lp::ch10;

namespace {

constexpr int kW = 160, kH = 90, kScale = 4;

// `shadows`: chapter 06's sun with its map, the one stage besides the lights that runs with MSAA.
WholeFrameSettings msaa_settings(int samples, bool shadows = false) {
  WholeFrameSettings s{.shadows = shadows, .clustered = false, .ao = false, .indirect = false, .neon = false,
                       .transparency = Method::Off, .msaa = samples};
  s.hdr.bloom = ch05::BloomMode::Off;  // bloom's reach is in pixels: it differs between the sizes
  return s;
}

ImageRGBA8 draw(WholeFrame& frame, const Scene& scene, int w, int h, const WholeFrameSettings& s,
                const char* view = "shops") {
  OutputTarget target(w, h);
  frame.render(frame_camera(scene.camera(view), float(w) / float(h)), {target.framebuffer(), w, h}, s, 1.f / 60.f, true);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  return target.read();
}

// The truth's pixel: the mean of its kScale x kScale sub-pixels in linear display light
// (what a display blends), encoded again; and its range, the largest channel difference
// between two of its sub-pixels (8-bit steps): 0 inside a flat surface, large across an edge.
struct Truth {
  ImageRGBA8 image;
  std::vector<int> range;
};
Truth downsample(const ImageRGBA8& big) {
  Truth t{ImageRGBA8::blank(kW, kH), std::vector<int>(std::size_t(kW) * kH, 0)};
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c) {
        double sum = 0;
        int lo = 255, hi = 0;
        for (int j = 0; j < kScale; ++j)
          for (int i = 0; i < kScale; ++i) {
            const int v = big.at(x * kScale + i, y * kScale + j)[c];
            sum += srgb_to_linear(float(v) / 255.f);
            lo = std::min(lo, v), hi = std::max(hi, v);
          }
        t.image.at(x, y)[c] = std::uint8_t(std::lround(255.f * linear_to_srgb(float(sum / (kScale * kScale)))));
        t.image.at(x, y)[3] = 255;
        int& r = t.range[std::size_t(y) * kW + x];
        r = std::max(r, hi - lo);
      }
  return t;
}

// The pixels MSAA marked (lit per sample), from --msaa-view edges: its red (light 1e4, 0, 0)
// leaves green and blue at 0 (and red above it) only where a pixel is marked, however many are.
std::vector<bool> marked_pixels(WholeFrame& frame, const Scene& scene, WholeFrameSettings s, const char* view = "shops") {
  s.msaa = 4;
  s.msaa_edges = true;
  const ImageRGBA8 edges = draw(frame, scene, kW, kH, s, view);
  std::vector<bool> marked(std::size_t(kW) * kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const std::uint8_t* p = edges.at(x, y);
      marked[std::size_t(y) * kW + x] = p[0] > 0 && p[1] == 0 && p[2] == 0;
    }
  return marked;
}

int channel_error(const ImageRGBA8& a, const ImageRGBA8& b, int x, int y) {
  int e = 0;
  for (int c = 0; c < 3; ++c) e = std::max(e, std::abs(int(a.at(x, y)[c]) - int(b.at(x, y)[c])));
  return e;
}

// An edge of the truth: sub-pixels that differ by more than this many steps (a visible edge,
// far above the few steps texture filtering moves a flat surface between the two sizes).
constexpr int kEdgeRange = 24;
// A flat pixel of the truth: its sub-pixels within a step of each other.
constexpr int kFlatRange = 1;

}  // namespace

// A straight edge crossing a pixel at a uniformly distributed coverage c: one sample at the
// centre errs by |c - [c > 1/2]| of the edge's contrast, 1/4 on average; four samples at four
// distinct offsets quantise c to quarters, an error of 1/16 on average: a quarter of the
// first. Edges are not all straight and the resolve's weights bend bright ones, so the test
// asks for half of that gain: the mean error on the truth's edges at most half of --msaa 1's.
// Flat pixels of the truth are lit once at their centre: within chapter 03's reference
// tolerance (3 steps) of the truth, on all but 0.1 % of them. (Not of --msaa 1: a pole thinner
// than the truth's grid is flat in the truth, and --msaa 1's one sample may hit it where MSAA's
// four, averaged, nearly do not.)
static void edges_nearer_the_truth(const WholeFrameSettings& settings, const char* path = "assets/street_shop/street_shop.gltf",
                                   const char* view = "shops") {
  const Scene scene = load_scene(from_root(path));
  WholeFrame frame(scene);
  auto with = [&](int samples) {
    WholeFrameSettings s = settings;
    s.msaa = samples;
    return s;
  };
  const Truth truth = downsample(draw(frame, scene, kW * kScale, kH * kScale, with(1), view));
  const ImageRGBA8 one = draw(frame, scene, kW, kH, with(1), view);
  const ImageRGBA8 four = draw(frame, scene, kW, kH, with(4), view);
  const std::vector<bool> marked = marked_pixels(frame, scene, settings, view);
  double e1 = 0, e4 = 0;
  int edges = 0, flat = 0, flat_off = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const int r = truth.range[std::size_t(y) * kW + x];
      if (r > kEdgeRange && marked[std::size_t(y) * kW + x]) {
        ++edges;
        e1 += channel_error(one, truth.image, x, y);
        e4 += channel_error(four, truth.image, x, y);
      } else if (r <= kFlatRange) {
        ++flat;
        flat_off += channel_error(four, truth.image, x, y) > 3;
      }
    }
  ASSERT_GT(edges, kW * kH / 100) << "the street should have edges";
  ASSERT_GT(flat, kW * kH / 10);
  e1 /= edges, e4 /= edges;
  std::printf("edges %d: mean error --msaa 1 %.2f, --msaa 4 %.2f steps; flat %d, %d off by more than 3\n", edges, e1, e4,
              flat, flat_off);
  EXPECT_LE(e4, e1 / 2) << "on " << edges << " edge pixels";
  EXPECT_LE(flat_off, flat / 1000) << "of " << flat << " flat pixels off the truth by more than 3 steps";
}
TEST(WholeFrameMsaaGl, EdgesAreNearerTheSupersampledTruthAndFlatPixelsUnchanged) { edges_nearer_the_truth(msaa_settings(1)); }

// The same with chapter 06's sun and its map (issue 26): its hook is read per sample on the
// marked edges and per pixel elsewhere, so the bounds above hold with the shadow in both the
// frame and its truth (the map is fitted to the view, not the pixels: the same map at both
// sizes). Without the map in the MSAA frame its flat pixels in the moon's shadow would be lit.
TEST(WholeFrameMsaaGl, WithTheSunsShadowEdgesAreNearerTheTruthAndFlatPixelsUnchanged) {
  edges_nearer_the_truth(msaa_settings(1, true));
}

// The same with chapter 04's tubes on the neon street (issue 26): their capsules light per sample
// on the marked edges and per pixel elsewhere, as the volume lights do, so the bounds above hold
// with the tubes' light (and their glass, drawn into the samples) in both the frame and its truth.
// Without the tubes in the MSAA frame its flat pixels under the signs would be darker.
TEST(WholeFrameMsaaGl, WithTheTubesEdgesAreNearerTheTruthAndFlatPixelsUnchanged) {
  WholeFrameSettings s = msaa_settings(1);
  s.neon = true;
  edges_nearer_the_truth(s, "assets/street_neon/street_neon.gltf", "neon_signs");
}

// The tubes' light on the marked edges alone (their capsules' second rate): on the
// marked pixels the tubes light (the truth with tubes against the truth without, by more than 3
// steps), --msaa 4's mean error at most half of --msaa 1's, the straight-edge bound above. Among
// the image's thousand edge pixels, the few dozen the tubes light weigh too little there.
TEST(WholeFrameMsaaGl, TheTubesLightTheMarkedEdges) {
  const Scene scene = load_scene(from_root("assets/street_neon/street_neon.gltf"));
  WholeFrame frame(scene);
  WholeFrameSettings s = msaa_settings(1);
  s.neon = true;
  const char* view = "neon_signs";
  const Truth truth = downsample(draw(frame, scene, kW * kScale, kH * kScale, s, view));
  const Truth dark = downsample(draw(frame, scene, kW * kScale, kH * kScale, msaa_settings(1), view));
  const ImageRGBA8 one = draw(frame, scene, kW, kH, s, view);
  s.msaa = 4;
  const ImageRGBA8 four = draw(frame, scene, kW, kH, s, view);
  const std::vector<bool> marked = marked_pixels(frame, scene, s, view);
  double e1 = 0, e4 = 0;
  int lit = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      if (!marked[std::size_t(y) * kW + x] || channel_error(truth.image, dark.image, x, y) <= 3) continue;
      ++lit;
      e1 += channel_error(one, truth.image, x, y);
      e4 += channel_error(four, truth.image, x, y);
    }
  std::printf("marked pixels the tubes light: %d: mean error --msaa 1 %.2f, --msaa 4 %.2f steps\n", lit, e1 / std::max(lit, 1),
              e4 / std::max(lit, 1));
  ASSERT_GT(lit, 20) << "the signs should light marked edges";
  EXPECT_LE(e4, e1 / 2) << "on " << lit << " marked pixels the tubes light";
}

// The marked pixels (lit per sample) are where the edges are, and few more. Every strong edge
// of the truth (sub-pixels half the display's range apart) is marked or beside a mark (the
// mark is made from the samples inside the pixel, the truth's range from its own sub-pixels:
// the two grids differ), on all but 5 % of them: a regression bound, not derived (a feature
// narrower than the gaps between MSAA's four samples can fall between all of them, and how
// many do depends on the scene); and the marks are at most the truth's visible edges, a bound
// on the per-sample work. (Not every mark lies on a truth's edge: a thin pole that MSAA's
// samples hit may fall between the truth's grid points.)
TEST(WholeFrameMsaaGl, MarkedPixelsCoverTheTruthsEdgesAndAreBounded) {
  const Scene scene = load_scene(from_root("assets/street_shop/street_shop.gltf"));
  WholeFrame frame(scene);
  const Truth truth = downsample(draw(frame, scene, kW * kScale, kH * kScale, msaa_settings(1)));
  const std::vector<bool> marked = marked_pixels(frame, scene, msaa_settings(1));
  ASSERT_NE(frame.msaa(), nullptr);
  int count = 0, visible = 0, strong = 0, strong_unmarked = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const int r = truth.range[std::size_t(y) * kW + x];
      count += marked[std::size_t(y) * kW + x];
      visible += r > kEdgeRange;
      if (r < 128) continue;
      ++strong;
      bool near = false;
      for (int j = std::max(0, y - 1); j <= std::min(kH - 1, y + 1); ++j)
        for (int i = std::max(0, x - 1); i <= std::min(kW - 1, x + 1); ++i) near = near || marked[std::size_t(j) * kW + i];
      strong_unmarked += !near;
    }
  std::printf("marked %d of %d pixels; %d visible edges in the truth; %d strong, %d with no mark beside\n", count,
              kW * kH, visible, strong, strong_unmarked);
  ASSERT_GT(strong, kW * kH / 100) << "the street should have strong edges";
  EXPECT_LE(strong_unmarked, strong / 20);
  EXPECT_GT(count, 0);
  EXPECT_LE(count, visible);
}

// The glass with MSAA (issue 26): drawn into the samples before the resolve, depth-tested against
// the multisampled depth, so a pane's edge is resolved as an opaque edge is. The pixels the glass
// changes (the truth with glass against the truth without, by more than chapter 03's 3 steps):
// on those of them the truth sees as edges, --msaa 4's mean error at most half of --msaa 1's (the
// straight-edge argument above). Few of them are flat (the glass lies over lit shop interiors),
// so the others are held by their own range r: a mean of sub-pixels that span r steps lies
// within r of each of them, so --msaa 4, whose samples fall among them, lies within r + 3 steps
// (chapter 03's tolerance) of the truth, on all but 1 % of them (a sample may land on a feature
// the truth's grid steps over, as with the poles above). Drawn after the resolve, one colour a
// pixel, the glass's edges would be --msaa 1's.
static void glass_edges_nearer_the_truth(Method method) {
  const Scene scene = load_scene(from_root("assets/street_shop/street_shop.gltf"));
  WholeFrame frame(scene);
  auto with_glass = [&](int samples) {  // and the sun's map, which the glass's hook reads per pixel
    WholeFrameSettings s = msaa_settings(samples, true);
    s.transparency = method;
    return s;
  };
  const Truth truth = downsample(draw(frame, scene, kW * kScale, kH * kScale, with_glass(1)));
  const Truth plain = downsample(draw(frame, scene, kW * kScale, kH * kScale, msaa_settings(1, true)));
  const ImageRGBA8 one = draw(frame, scene, kW, kH, with_glass(1));
  const ImageRGBA8 four = draw(frame, scene, kW, kH, with_glass(4));
  double e1 = 0, e4 = 0;
  int edges = 0, flat = 0, flat_off = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      if (channel_error(truth.image, plain.image, x, y) <= 3) continue;  // no glass here
      const int r = truth.range[std::size_t(y) * kW + x];
      if (r > kEdgeRange) {
        ++edges;
        e1 += channel_error(one, truth.image, x, y);
        e4 += channel_error(four, truth.image, x, y);
      } else {
        ++flat;
        flat_off += channel_error(four, truth.image, x, y) > r + 3;
      }
    }
  ASSERT_GT(edges, 20) << "the shop windows' glass should have edges";
  ASSERT_GT(flat, 100) << "and pixels inside it";
  e1 /= edges, e4 /= edges;
  std::printf("glass (%s): edges %d: mean error --msaa 1 %.2f, --msaa 4 %.2f steps; inside %d, %d off by more than r + 3\n",
              kMethods[std::size_t(method)].c_str(), edges, e1, e4, flat, flat_off);
  EXPECT_LE(e4, e1 / 2) << "on " << edges << " pixels of the glass's edges";
  EXPECT_LE(flat_off, flat / 100) << "of " << flat << " pixels inside the glass off the truth by more than their range + 3 steps";
}
TEST(WholeFrameMsaaGl, SortedGlassEdgesAreNearerTheTruthAndItsInsideWithinRange) { glass_edges_nearer_the_truth(Method::Sorted); }
TEST(WholeFrameMsaaGl, WboitGlassEdgesAreNearerTheTruthAndItsInsideWithinRange) { glass_edges_nearer_the_truth(Method::Wboit); }

// Bad input: a sample count the renderer cannot make is refused with what and why.
TEST(WholeFrameMsaaGl, ASampleCountOutOfRangeIsRefused) {
  const Scene scene = load_scene(from_root("assets/street_shop/street_shop.gltf"));
  WholeFrame frame(scene);
  OutputTarget target(32, 18);
  WholeFrameSettings s = msaa_settings(3);
  try {
    frame.render(frame_camera(scene.camera("shops"), 32.f / 18.f), {target.framebuffer(), 32, 18}, s, 1.f / 60.f, true);
    FAIL() << "3 samples were accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("3 samples per pixel: use 1, 2, 4 or 8"), std::string::npos) << e.what();
  }
}
