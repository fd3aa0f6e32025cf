// Chapter 06's metrics (shadow_metrics.h) on crafted images whose answers are counted by hand,
// and the filtered hard truth on a crafted scene whose answer is a closed form: a plane half
// covered by a roof under a sun straight overhead, where the box filter of the hard shadow is
// a ramp as wide as the footprint.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/06_shadows/shadow_metrics.h"
#include "common/error.h"

using namespace lp;
using namespace lp::ch06;

namespace {

// A reference image: every pixel in the mask, lit (1) in both visibility channels.
ImageF lit_reference(int w, int h) {
  ImageF t = ImageF::blank(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) t.at(x, y, 0) = t.at(x, y, 1) = t.at(x, y, 2) = 1.f;
  return t;
}
ImageF method(int w, int h, float value) {
  ImageF v = ImageF::blank(w, h, 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) v.at(x, y, 0) = v.at(x, y, 1) = v.at(x, y, 2) = value;
  return v;
}
std::size_t count(const std::vector<bool>& v) { return std::size_t(std::count(v.begin(), v.end(), true)); }

}  // namespace

// One pixel strictly between 0 and 1 makes a penumbra of (2 band + 1)^2 pixels; values of
// exactly 0 and 1 are no penumbra; pixels outside the mask are never in it, even in the band.
TEST(PenumbraMetric, ThePenumbraIsTheStrictlyPartialPixelsWidenedByTheBand) {
  ImageF t = lit_reference(20, 20);
  t.at(3, 3, 1) = 0.f;  // full shadow: not penumbra
  EXPECT_EQ(count(penumbra_pixels(t, 1, 2)), 0u);
  t.at(10, 10, 1) = 0.5f;
  EXPECT_EQ(count(penumbra_pixels(t, 1, 0)), 1u);
  EXPECT_EQ(count(penumbra_pixels(t, 1, 2)), 25u);
  EXPECT_EQ(count(penumbra_pixels(t, 1, 3)), 49u);
  EXPECT_EQ(count(penumbra_pixels(t, 0, 2)), 0u);  // the hard channel has none
  t.at(12, 12, 2) = 0.f;                           // the band's corner leaves the mask
  const std::vector<bool> p = penumbra_pixels(t, 1, 2);
  EXPECT_EQ(count(p), 24u);
  EXPECT_FALSE(p[12 * 20 + 12]);
  EXPECT_TRUE(p[8 * 20 + 8]);
  EXPECT_FALSE(p[7 * 20 + 10]);  // three rows up: outside a band of two
  // At the image's border the band is cut, not wrapped.
  t.at(0, 0, 1) = 0.01f;
  EXPECT_EQ(count(penumbra_pixels(t, 1, 2)), 24u + 9u);
  EXPECT_THROW(penumbra_pixels(t, 3, 2), Error);
}

// The penumbra error is the mean over the penumbra only: a method wrong everywhere else by 1
// scores what it does inside; an excluded pixel does not count.
TEST(PenumbraMetric, TheErrorIsTheMeanOverThePenumbraAlone) {
  ImageF t = lit_reference(16, 16);
  for (int x = 0; x < 16; ++x) t.at(x, 8, 1) = 0.5f;  // a row of penumbra: 5 rows with the band
  ImageF v = method(16, 16, 0.f);                      // wrong by 1 outside, 0.5 on the row
  for (int x = 0; x < 16; ++x) v.at(x, 8, 0) = 0.75f;  // 0.25 on the row itself
  const PenumbraError e = penumbra_error(v, t, 1, nullptr, 2);
  EXPECT_EQ(e.pixels, 16u * 5u);
  EXPECT_NEAR(e.mean_abs, (16 * 0.25 + 64 * 1.0) / 80.0, 1e-12);
  EXPECT_NEAR(e.mean_signed, (16 * 0.25 - 64 * 1.0) / 80.0, 1e-12);  // the band's rows: lit in the truth, dark here
  EXPECT_NEAR(penumbra_error(v, t, 1, nullptr, 0).mean_abs, 0.25, 1e-12);
  std::vector<bool> exclude(16 * 16, false);
  for (int x = 0; x < 16; ++x) exclude[std::size_t(6 * 16 + x)] = true;  // one band row left out
  const PenumbraError left = penumbra_error(v, t, 1, &exclude, 2);
  EXPECT_EQ(left.pixels, 64u);
  EXPECT_NEAR(left.mean_abs, (16 * 0.25 + 48 * 1.0) / 64.0, 1e-12);
  // No penumbra: nothing counted, no error (not a division by zero).
  const PenumbraError none = penumbra_error(v, lit_reference(16, 16), 1);
  EXPECT_EQ(none.pixels, 0u);
  EXPECT_EQ(none.mean_abs, 0.0);
  // Images of different sizes are named, not read past their end.
  EXPECT_THROW(penumbra_error(method(8, 16, 0.f), t, 1), Error);
  exclude.push_back(false);  // one entry too many
  EXPECT_THROW(penumbra_error(v, t, 1, &exclude), Error);
}

// A leak is a pixel in full shadow (soft truth exactly 0) that the method lights above 0.1:
// 0.1 itself is not; a pixel of the penumbra or outside the mask never counts.
TEST(PenumbraMetric, LeaksAreFullShadowPixelsLitAboveTheThreshold) {
  ImageF t = lit_reference(10, 1);
  for (int x = 0; x < 6; ++x) t.at(x, 0, 1) = 0.f;  // pixels 0..5 in full shadow
  t.at(5, 0, 2) = 0.f;                              // ... but 5 is not in the mask
  t.at(6, 0, 1) = 0.5f;                             // penumbra
  ImageF v = method(10, 1, 0.f);
  v.at(0, 0, 0) = 0.1f;   // at the threshold: not a leak
  v.at(1, 0, 0) = 0.11f;  // a leak
  v.at(2, 0, 0) = 1.f;    // a leak
  v.at(5, 0, 0) = 1.f;    // outside the mask
  v.at(6, 0, 0) = 1.f;    // penumbra
  LightLeak l = light_leak(v, t);
  EXPECT_EQ(l.full_shadow, 5u);
  EXPECT_EQ(l.leaking, 2u);
  std::vector<bool> exclude(10, false);
  exclude[2] = true;
  l = light_leak(v, t, &exclude);
  EXPECT_EQ(l.full_shadow, 4u);
  EXPECT_EQ(l.leaking, 1u);
}

// show_visibility.frag's blue (sky, facing away) is what the metrics leave out as a silhouette.
TEST(PenumbraMetric, TheMethodsBlueIsOutsideItsMask) {
  ImageF v = method(3, 1, 0.5f);
  v.at(0, 0, 0) = 0.05f, v.at(0, 0, 1) = 0.1f, v.at(0, 0, 2) = 0.5f;  // blue
  v.at(1, 0, 0) = 0.f, v.at(1, 0, 1) = 0.f, v.at(1, 0, 2) = 0.f;      // shadow: black, not blue
  const std::vector<bool> out = outside_method_mask(v);
  EXPECT_TRUE(out[0]);
  EXPECT_FALSE(out[1]);
  EXPECT_FALSE(out[2]);
}

// The footprint: k texels of the fitted box along each light axis, the axes across the light.
TEST(FilteredHardTruth, TheFootprintIsTheKernelsTexelsInTheLightsPlane) {
  const glm::vec3 direction = glm::normalize(glm::vec3(0.3f, -1.f, 0.2f));
  const LightFrustum f = fit_light_frustum(direction, glm::vec3(-4, 0, -2), glm::vec3(4, 3, 2));
  const KernelFootprint fp = kernel_footprint(f, 512, 5);
  EXPECT_NEAR(glm::dot(fp.to_sun, -direction), 1.f, 1e-5f);
  EXPECT_NEAR(glm::dot(fp.axis_u, fp.to_sun), 0.f, 1e-5f);
  EXPECT_NEAR(glm::dot(fp.axis_v, fp.to_sun), 0.f, 1e-5f);
  EXPECT_NEAR(fp.width_u, 5.f * (f.box_max.x - f.box_min.x) / 512.f, 1e-6f);
  EXPECT_NEAR(fp.width_v, 5.f * (f.box_max.y - f.box_min.y) / 512.f, 1e-6f);
  EXPECT_NEAR(std::max(fp.width_u, fp.width_v), 5.f * f.texel_world(512), 1e-6f);
  EXPECT_THROW(kernel_footprint(f, 0, 3), Error);
  EXPECT_THROW(kernel_footprint(f, 512, 0), Error);
}

namespace {
// Two quads: the floor y = 0 (x, z in [-4, 4]) and a roof at y = 1 over x < 0, both facing up.
Scene floor_and_roof() {
  Scene s;
  auto quad = [&](float x0, float x1, float y) {
    const std::uint32_t base = std::uint32_t(s.vertices.size());
    for (glm::vec3 p : {glm::vec3(x0, y, -4), glm::vec3(x1, y, -4), glm::vec3(x1, y, 4), glm::vec3(x0, y, 4)}) {
      Vertex v;
      v.position = p;
      s.vertices.push_back(v);
    }
    for (std::uint32_t i : {0u, 2u, 1u, 0u, 3u, 2u}) s.indices.push_back(base + i);  // counter-clockwise from above
  };
  quad(-4, 4, 0);
  quad(-4, 0, 1);
  Material m;
  m.double_sided = true;
  s.materials.push_back(m);
  s.meshes.push_back({"quads", {{0, std::uint32_t(s.indices.size()), 0}}});
  Instance i;
  i.name = "quads", i.mesh = 0;
  s.instances.push_back(i);
  return s;
}
}  // namespace

// Under a sun straight overhead the roof's hard shadow ends at x = 0 on the floor; box-filtered
// over a footprint w wide it is the ramp clamp(1/2 + x / w, 0, 1). A camera 0.5 m over the floor
// (under the roof's height, so it sees the floor beneath it) looks straight down. Per pixel the
// jittered s x s grid can be wrong by at most one column of strata, 1/s; the roof's edge is
// exactly one column only where it crosses it, so the bound is 1/s, no noise allowance.
// Seen failing: the samples spread over half the footprint.
TEST(FilteredHardTruth, AHalfPlanesShadowFilteredIsARampAsWideAsTheFootprint) {
  const Scene scene = floor_and_roof();
  const RayScene rays(scene);
  Camera c;
  c.world = glm::inverse(glm::lookAt(glm::vec3(0, 0.5f, 0), glm::vec3(0, 0, 0), glm::vec3(0, 0, -1)));
  const int w = 64, h = 64;
  const FrameCamera cam = frame_camera(c, 1.f);
  KernelFootprint fp;
  fp.to_sun = {0, 1, 0}, fp.axis_u = {1, 0, 0}, fp.axis_v = {0, 0, 1};
  fp.width_u = fp.width_v = 0.2f;
  const int strata = 8;
  const ImageF t = filtered_hard_truth(rays, cam, w, h, fp, strata);
  const auto hits = primary_hits(rays, cam, w, h);
  double worst = 0;
  std::size_t ramp = 0, masked = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const auto& hit = hits[std::size_t(y) * w + x];
      ASSERT_TRUE(hit.has_value());
      ASSERT_EQ(t.at(x, y, 2), 1.f);
      ++masked;
      const float expected = std::clamp(0.5f + hit->position.x / fp.width_u, 0.f, 1.f);
      ramp += expected > 0.f && expected < 1.f;
      worst = std::max(worst, double(std::abs(t.at(x, y, 0) - expected)));
    }
  std::printf("%zu of %zu pixels on the ramp, worst |error| %.4f\n", ramp, masked, worst);
  EXPECT_GT(ramp, std::size_t(w * 4));  // the ramp spans pixels to measure
  EXPECT_LE(worst, 1.0 / strata + 1e-6);
}

// On a receiver tilted across the light the footprint's points lie on the receiver's plane, not
// on the light's: the floor tilted about z (y = x / 2) under the same sun. Its hard edge is where
// the tilted plane meets the roof's shadow (x = 0); a point of the box at offset u across the
// light lands on the plane at x = u, so the filtered ramp is clamp(1/2 + x / w) again in x, the
// same as on the flat floor; points taken on the light's plane through the pixel's point
// instead would start under the floor on one side and above it on the other (seen failing so).
TEST(FilteredHardTruth, OnATiltedReceiverTheFootprintLiesOnItsPlane) {
  Scene scene = floor_and_roof();
  // Tilt the floor (its first four vertices) about z.
  for (int i = 0; i < 4; ++i) {
    Vertex& v = scene.vertices[std::size_t(i)];
    v.position.y = 0.5f * v.position.x;  // a slope of 1:2, below the roof (y < 1) for x < 2
  }
  const RayScene rays(scene);
  Camera c;
  c.world = glm::inverse(glm::lookAt(glm::vec3(0, 0.5f, 0), glm::vec3(0, -1, 0), glm::vec3(0, 0, -1)));
  const int w = 64, h = 64;
  const FrameCamera cam = frame_camera(c, 1.f);
  KernelFootprint fp;
  fp.to_sun = {0, 1, 0}, fp.axis_u = {1, 0, 0}, fp.axis_v = {0, 0, 1};
  fp.width_u = fp.width_v = 0.2f;
  const int strata = 8;
  const ImageF t = filtered_hard_truth(rays, cam, w, h, fp, strata);
  const auto hits = primary_hits(rays, cam, w, h);
  double worst = 0;
  std::size_t ramp = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const auto& hit = hits[std::size_t(y) * w + x];
      if (!hit || t.at(x, y, 2) < 0.5f || hit->position.y > 0.9f) continue;  // the floor only
      const float expected = std::clamp(0.5f + hit->position.x / fp.width_u, 0.f, 1.f);
      ramp += expected > 0.f && expected < 1.f;
      worst = std::max(worst, double(std::abs(t.at(x, y, 0) - expected)));
    }
  std::printf("tilted: %zu pixels on the ramp, worst |error| %.4f\n", ramp, worst);
  EXPECT_GT(ramp, std::size_t(w * 4));
  EXPECT_LE(worst, 1.0 / strata + 1e-6);
}
