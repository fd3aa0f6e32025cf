// Chapter 09's grid maths on the CPU (cluster_grid.h; shaders/grid.glsl is its twin): the
// exponential slices and the sphere-against-cell test the assignment relies on.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/09_clustered/cluster_grid.h"
#include "tests/unit/capsule_cases.h"

using namespace lp;
using namespace lp::ch09;

namespace {
FrameCamera test_camera() { return test::grid_test_camera(); }  // at the origin, looking down -z
const Grid kDoom = grid_of_counts(1920, 1080, 16, 9, 24, 0.1f, 100.f);
}  // namespace

TEST(ClusterGrid, DoomsPresetIs16By9By24OverTheImage) {
  EXPECT_EQ(kDoom.tiles_x, 16);
  EXPECT_EQ(kDoom.tiles_y, 9);
  EXPECT_EQ(kDoom.slices, 24);
  EXPECT_EQ(kDoom.tile_w, 120);
  EXPECT_EQ(kDoom.tile_h, 120);
  EXPECT_EQ(kDoom.cells(), 3456);
  const Grid odd = grid_of_tiles(100, 50, 16, 1, 0.1f, 100.f);  // the last column and row cut short
  EXPECT_EQ(odd.tiles_x, 7);
  EXPECT_EQ(odd.tiles_y, 4);
}

TEST(ClusterGrid, ExponentialSlicesGrowByAConstantRatio) {
  EXPECT_FLOAT_EQ(slice_start(kDoom, 0), 0.1f);
  EXPECT_FLOAT_EQ(slice_start(kDoom, 24), 100.f);
  const double ratio = std::pow(1000.0, 1.0 / 24.0);  // (far / near)^(1 / S)
  for (int k = 0; k < 24; ++k)
    EXPECT_NEAR(slice_start(kDoom, k + 1) / slice_start(kDoom, k), ratio, 1e-4) << "slice " << k;
  for (int k = 0; k < 24; ++k) {  // a depth inside a slice finds that slice
    const float mid = std::sqrt(slice_start(kDoom, k) * slice_start(kDoom, k + 1));
    EXPECT_EQ(slice_of(kDoom, mid), k);
  }
  EXPECT_EQ(slice_of(kDoom, 0.01f), 0);    // before the near plane: the first slice
  EXPECT_EQ(slice_of(kDoom, 1000.f), 23);  // past the far plane: the last
}

TEST(ClusterGrid, ANearSliceSpansTheNearMetresAndTheRestGrowByAConstantRatio) {
  // Slice 0 is znear .. 5 m; the other 23 are exponential from 5 m to 100 m: a ratio of 20^(1/23).
  Grid g = kDoom;
  g.near_slice = 5.f;
  ASSERT_TRUE(g.has_near_slice());
  EXPECT_FLOAT_EQ(slice_start(g, 0), 0.1f);
  EXPECT_FLOAT_EQ(slice_start(g, 1), 5.f);
  EXPECT_FLOAT_EQ(slice_start(g, 24), 100.f);
  const double ratio = std::pow(20.0, 1.0 / 23.0);
  for (int k = 1; k < 24; ++k)
    EXPECT_NEAR(slice_start(g, k + 1) / slice_start(g, k), ratio, 1e-4) << "slice " << k;
  for (int k = 0; k < 24; ++k) {  // a depth inside a slice finds that slice
    const float mid = std::sqrt(slice_start(g, k) * slice_start(g, k + 1));
    EXPECT_EQ(slice_of(g, mid), k) << "slice " << k;
  }
  EXPECT_EQ(slice_of(g, 4.99f), 0);
  EXPECT_EQ(slice_of(g, 5.01f), 1);
  EXPECT_EQ(slice_of(g, 0.01f), 0);
  EXPECT_EQ(slice_of(g, 1000.f), 23);
  // None at or before the near plane, or with one slice: the exponential slices as they were.
  for (const float none : {0.f, 0.1f}) {
    g.near_slice = none;
    EXPECT_FALSE(g.has_near_slice());
    EXPECT_EQ(slice_start(g, 5), slice_start(kDoom, 5));
  }
}

TEST(ClusterGrid, ACellBoxHoldsTheFrustumPieceOverItsPixels) {
  const FrameCamera c = test_camera();
  const Box b = cluster_box(c, kDoom, 0, 0, 10);
  // The bottom-left corner ray at the slice's far depth lies in the box.
  const float d = slice_start(kDoom, 11);
  const float t = std::tan(c.yfov / 2);
  const glm::vec3 corner(-d * t * c.aspect, -d * t, -d);
  EXPECT_TRUE(glm::all(glm::lessThanEqual(b.lo, corner + 1e-4f * d)));
  EXPECT_TRUE(glm::all(glm::greaterThanEqual(b.hi, corner - 1e-4f * d)));
  EXPECT_LE(b.hi.z, -slice_start(kDoom, 10) * (1 - kDepthPad) + 1e-6f);
}

TEST(ClusterGrid, ASphereStraddlingTwoSlicesMeetsBoth) {
  const FrameCamera c = test_camera();
  const float boundary = slice_start(kDoom, 12);
  // Centre tile's centre ray, 1 cm before the boundary, radius 5 cm: it reaches slice 12 too.
  const glm::vec3 centre(0, 0, -(boundary - 0.01f));
  EXPECT_TRUE(sphere_meets_box(centre, 0.05f, cluster_box(c, kDoom, 8, 4, 11)));
  EXPECT_TRUE(sphere_meets_box(centre, 0.05f, cluster_box(c, kDoom, 8, 4, 12)));
  EXPECT_FALSE(sphere_meets_box(centre, 0.05f, cluster_box(c, kDoom, 8, 4, 14)));
  EXPECT_FALSE(sphere_meets_box(centre, 0.005f, cluster_box(c, kDoom, 8, 4, 12))) << "too small to reach it";
}

TEST(ClusterGrid, ALightBehindTheCameraMeetsNoCellUnlessItReachesPastTheNearPlane) {
  const FrameCamera c = test_camera();
  const glm::vec3 behind(0, 0, 2);  // 2 m behind the eye
  for (int k = 0; k < 24; ++k) EXPECT_FALSE(sphere_meets_box(behind, 1.5f, cluster_box(c, kDoom, 8, 4, k))) << k;
  EXPECT_TRUE(sphere_meets_box(behind, 2.2f, cluster_box(c, kDoom, 8, 4, 0)));  // reaches 0.2 m in front
}

TEST(ClusterGrid, ALightHoldingTheCameraMeetsEveryNearCell) {
  const FrameCamera c = test_camera();
  for (int ty = 0; ty < 9; ++ty)
    for (int tx = 0; tx < 16; ++tx) EXPECT_TRUE(sphere_meets_box(glm::vec3(0), 0.5f, cluster_box(c, kDoom, tx, ty, 0)));
  EXPECT_FALSE(sphere_meets_box(glm::vec3(0), 0.5f, cluster_box(c, kDoom, 8, 4, 23)));
}

TEST(ClusterGrid, ASphereBesideATileMissesItAndTheTestIsConservativeByLittle) {
  const FrameCamera c = test_camera();
  const Box b = cluster_box(c, kDoom, 8, 4, 12);
  const glm::vec3 outside(b.hi.x + 0.1f, 0.5f * (b.lo.y + b.hi.y), 0.5f * (b.lo.z + b.hi.z));
  EXPECT_FALSE(sphere_meets_box(outside, 0.099f, b));
  EXPECT_TRUE(sphere_meets_box(outside, 0.1f, b));  // touching counts
}

// A tube binned as its capsule (capsule_meets_box): one running down the centre ray through
// slices 5 to 15 meets every cell it crosses, even thin, and none past its ends or beside it.
TEST(ClusterGrid, ATubeCrossingSlicesMeetsEveryCellItCrosses) {
  const FrameCamera c = test_camera();
  const glm::vec3 a(0, 0, -slice_start(kDoom, 5) * 1.01f), b(0, 0, -slice_start(kDoom, 16) * 0.99f);
  for (int k = 0; k < 24; ++k) {
    const bool crossed = k >= 5 && k <= 15;
    EXPECT_EQ(capsule_meets_box(a, b, 1e-3f, cluster_box(c, kDoom, 8, 4, k)), crossed) << "slice " << k;
    EXPECT_EQ(capsule_meets_box(b, a, 1e-3f, cluster_box(c, kDoom, 8, 4, k)), crossed) << "reversed, slice " << k;
  }
  EXPECT_FALSE(capsule_meets_box(a, b, 1e-3f, cluster_box(c, kDoom, 2, 4, 10))) << "a tile beside it";
  // Along the image: a tube across the tiles of one slice, at its middle depth.
  const float d = std::sqrt(slice_start(kDoom, 12) * slice_start(kDoom, 13)), t = std::tan(c.yfov / 2) * d;
  const glm::vec3 left(-0.9f * t * c.aspect, 0.01f * t, -d), right(0.9f * t * c.aspect, 0.01f * t, -d);
  for (int tx = 1; tx < 15; ++tx) EXPECT_TRUE(capsule_meets_box(left, right, 1e-3f, cluster_box(c, kDoom, tx, 4, 12))) << tx;
  EXPECT_FALSE(capsule_meets_box(left, right, 1e-3f, cluster_box(c, kDoom, 8, 1, 12)));
}

// Against the exact distance from the segment to the box (a convex function along the segment,
// minimised by ternary search in double): every capsule that reaches a box meets it, and one
// that meets it reaches within sqrt(3) x its radius (the grown box's corners), on random
// capsules and boxes, axis-parallel and zero-length segments among them.
TEST(ClusterGrid, ACapsuleMeetsEveryBoxItReachesAndNoneFartherThanTheGrownCorners) {
  std::uint32_t state = 12345u;
  auto uniform = [&](float lo, float hi) {
    state = state * 1664525u + 1013904223u;
    return lo + (hi - lo) * float(state >> 8) / float(1u << 24);
  };
  int met = 0, missed = 0;
  for (int i = 0; i < 20000; ++i) {
    Box box;
    const glm::vec3 centre(uniform(-5, 5), uniform(-5, 5), uniform(-20, -1)), half(uniform(0.01f, 2), uniform(0.01f, 2), uniform(0.01f, 2));
    box.lo = centre - half;
    box.hi = centre + half;
    glm::vec3 a(uniform(-10, 10), uniform(-10, 10), uniform(-25, 0)), b(uniform(-10, 10), uniform(-10, 10), uniform(-25, 0));
    if (i % 5 == 1) b = a;                                   // zero length
    if (i % 5 == 2) b = glm::vec3(a.x, a.y, uniform(-25, 0));  // parallel to z
    if (i % 5 == 3) b = glm::vec3(uniform(-10, 10), a.y, a.z);  // parallel to x
    const float r = uniform(0.001f, 4);
    const double distance = test::segment_box_distance(a, b, box);
    const bool meets = capsule_meets_box(a, b, r, box);
    met += meets;
    missed += !meets;
    if (distance <= double(r)) {
      ASSERT_TRUE(meets) << "case " << i << ": the capsule reaches the box (" << distance << " <= " << r << ") and is not binned";
    }
    if (distance > std::sqrt(3.0) * double(r) * (1 + 1e-4) + 1e-5) {
      ASSERT_FALSE(meets) << "case " << i << ": binned at " << distance << ", more than sqrt 3 x " << r;
    }
  }
  EXPECT_GT(met, 2000);
  EXPECT_GT(missed, 2000);
}

// The hard case of the tubes' binning: a capsule that touches a cell's box by less than float
// rounding (capsule_cases.h: the camera 150 m from the origin, the tube beside a face of a
// cluster's box at exactly its cut distance in exact arithmetic, and the radius at least what
// neon_light()'s float distance from the face point gives). The float path (view transform,
// then the slab test) must bin every one; without the rounding margin a share of them is
// dropped (the mutation), and with it the cost is a fraction of a millimetre.
TEST(ClusterGrid, ACapsuleTouchingABoxByLessThanItsRoundingIsBinned) {
  const std::vector<test::CapsuleCase> cases = test::touching_capsules(test_camera(), kDoom, 4000);
  int dropped = 0;
  double widest_margin = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const test::CapsuleCase& k = cases[i];
    if (!capsule_meets_box(k.a, k.b, k.radius, k.box, k.eye_distance) && ++dropped <= 5)
      ADD_FAILURE() << "case " << i << ": the cut reaches the box (exact " << k.exact << ", shaded " << k.shaded
                    << ", radius " << k.radius << ") and the capsule is not binned";
    widest_margin = std::max(widest_margin, double(capsule_rounding_margin(k.a, k.b, k.radius, k.box, k.eye_distance)));
  }
  EXPECT_EQ(dropped, 0) << "of " << cases.size();
  EXPECT_LT(widest_margin, 1e-3) << "the margin is rounding's, not a visible growth";
  EXPECT_GT(widest_margin, 1e-5) << "it covers more than the old padding did";
}

// Harada's 2.5D mask: 32 equal bins over the tile's depth range.
TEST(ClusterGrid, DepthBinsCutTheTileRangeIn32AndClampOutside) {
  EXPECT_EQ(depth_bin(10.f, 42.f, 10.f), 0);
  EXPECT_EQ(depth_bin(10.f, 42.f, 10.99f), 0);
  EXPECT_EQ(depth_bin(10.f, 42.f, 11.f), 1);   // bins of 1 m
  EXPECT_EQ(depth_bin(10.f, 42.f, 41.5f), 31);
  EXPECT_EQ(depth_bin(10.f, 42.f, 42.f), 31);  // the far bound is in the last bin, not past it
  EXPECT_EQ(depth_bin(10.f, 42.f, -1e30f), 0);
  EXPECT_EQ(depth_bin(10.f, 42.f, 1e30f), 31);
  EXPECT_EQ(depth_bin(5.f, 5.f, 5.f), 0) << "a flat tile: one bin, no division by zero";
  EXPECT_EQ(depth_range_bits(10.f, 42.f, 12.5f, 14.5f), 0b11100u);
  EXPECT_EQ(depth_range_bits(10.f, 42.f, 0.f, 1000.f), 0xFFFFFFFFu);
  EXPECT_EQ(depth_range_bits(10.f, 42.f, 41.2f, 41.3f), 1u << 31);
}

// The case the mask is for: a post 2 m away in front of a wall 30 m away share a tile. A light
// 15 m away in the gap meets the tile's box, but its depth extent holds neither surface's bin;
// a light at the wall keeps the wall's bin, and one reaching the post the post's.
TEST(ClusterGrid, TheDepthMaskDropsALightInTheGapOfADepthDiscontinuity) {
  const float lo = 2.f, hi = 30.f;
  const std::uint32_t tile = (1u << depth_bin(lo, hi, 2.f)) | (1u << depth_bin(lo, hi, 30.f));
  EXPECT_EQ(tile, 1u | (1u << 31));
  EXPECT_EQ(light_depth_bits(lo, hi, 15.f, 3.f) & tile, 0u);
  EXPECT_NE(light_depth_bits(lo, hi, 29.f, 1.f) & tile, 0u);
  EXPECT_NE(light_depth_bits(lo, hi, 4.f, 2.f) & tile, 0u) << "reaches the post exactly: kept (padded)";
  // Conservative by the padding, and by little: a light stopping 1 cm short of the post's bin
  // edge is dropped; kDepthPad x 30 m = 3 mm of slack.
  const float bin = (hi - lo) / 32.f;
  EXPECT_EQ(light_depth_bits(lo, hi, 2.f + bin + 1.01f + 0.01f, 1.f) & 1u, 0u);
  EXPECT_NE(light_depth_bits(lo, hi, 2.f + bin + 1.f - 0.002f, 1.f) & 1u, 0u);
}

// The density knob (density.h): a scaled light's cut is s times as far, so the lit pairs at
// a stated density come from lights of a stated size; the fit reaches its target or says not.
#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/09_clustered/density.h"
#include "common/error.h"

TEST(Density, AScaledLightsCutScalesWithIt) {
  Light lamp;
  lamp.intensity = 40.f;
  lamp.range = 6.f;
  lamp.color = glm::vec3(1.f, 0.8f, 0.5f);
  Light sun;
  sun.type = LightType::Directional;
  sun.intensity = 3.f;
  const float threshold = 1e-3f;
  const float cut = ch03::light_radius(lamp, threshold);
  ASSERT_GT(cut, 1.f);
  ASSERT_LT(cut, lamp.range);
  for (const float s : {0.177f, 0.5f, 2.f, 7.f}) {
    const std::vector<Light> scaled = scaled_lights({lamp, sun}, s);
    EXPECT_NEAR(ch03::light_radius(scaled[0], threshold), s * cut, 1e-4f * s * cut) << s;
    EXPECT_EQ(scaled[1].intensity, sun.intensity) << "a directional light has no size";
  }
  EXPECT_THROW(scaled_lights({lamp}, 0.f), Error);
  EXPECT_THROW(scaled_lights({lamp}, std::nanf("")), Error);
}

TEST(Density, TheFitReachesItsTargetOrSaysItDidNot) {
  int calls = 0;
  // Small lights in a big scene: density ~ s^3; the first step alone lands on it.
  DensityFit f = fit_density(32, 1.f, [&](float s) { ++calls; return 3.0 * s * s * s; });
  EXPECT_TRUE(f.met);
  EXPECT_NEAR(f.density, 32.0, 32 * 0.03);
  EXPECT_EQ(f.steps, calls);
  EXPECT_EQ(f.steps, 2) << "the start, then one step";
  // Lights as large as a slab: density ~ s^1.5 past s = 1; the secant finds the exponent.
  f = fit_density(128, 0.5f, [](float s) { return s < 1 ? 10.0 * s * s * s : 10.0 * std::pow(double(s), 1.5); });
  EXPECT_TRUE(f.met);
  EXPECT_NEAR(f.density, 128.0, 128 * 0.03);
  EXPECT_LE(f.steps, 8);
  // Steep: density ~ s^11 (a million lights at 8 a pixel on the H200 rose from 4.1 to 14.4
  // over a 12 % change of scale); and steeper past the target (s^14). The fit brackets the
  // target and converges; a secant from the last two points alone overshot to and fro.
  for (const double above : {11.0, 14.0}) {
    SCOPED_TRACE("s^11 below the target, s^" + std::to_string(int(above)) + " above");
    f = fit_density(8, 1.f, [&](float s) {
      const double x = double(s) / 0.15;
      return 8.0 * std::pow(x, x < 1 ? 11.0 : above);
    });
    EXPECT_TRUE(f.met) << "density " << f.density << " after " << f.steps << " steps";
    EXPECT_NEAR(f.density, 8.0, 8 * 0.03);
    EXPECT_LE(f.steps, 8);
  }
  // Unreachable (the density saturates at 20): bounded, the best found, and not met.
  calls = 0;
  f = fit_density(128, 1.f, [&](float s) { ++calls; return std::min(20.0, 5.0 * s); });
  EXPECT_FALSE(f.met);
  EXPECT_EQ(f.density, 20.0);
  EXPECT_LE(calls, 8);
  EXPECT_THROW(fit_density(0, 1.f, [](float) { return 1.0; }), Error);
}

TEST(Density, MedianAndPercentile) {
  EXPECT_EQ(quantile({5, 1, 4, 2, 3}, 0.5), 3.0);
  EXPECT_NEAR(quantile({5, 1, 4, 2, 3}, 0.95), 4.8, 1e-12);
  EXPECT_EQ(quantile({7}, 0.95), 7.0);
  EXPECT_EQ(quantile({}, 0.5), 0.0);
}

TEST(Density, ViewsAlongTheStreetKeepTheirDirection) {
  Camera c;
  c.name = "v";
  c.world = glm::translate(glm::mat4(1.f), glm::vec3(2, 1.7f, 55)) * glm::rotate(glm::mat4(1.f), 0.3f, glm::vec3(0, 1, 0));
  const std::vector<Camera> v = views_along(c, 3, 10.f);
  ASSERT_EQ(v.size(), 3u);
  const glm::vec3 forward = -glm::vec3(c.world[2]);
  EXPECT_NEAR(glm::distance(v[2].position(), c.position()), 20.f, 1e-4f);
  EXPECT_NEAR(v[1].position().y, c.position().y, 1e-5f) << "moved along the ground";
  EXPECT_GT(glm::dot(v[1].position() - c.position(), forward), 9.f);
  EXPECT_EQ(glm::vec3(v[2].world[2]), glm::vec3(c.world[2]));
}

// Z-binning's screen rectangle holds the sphere: points on spheres all around the view
// (straddling the near plane, off to the sides, far), projected to pixels, each fall in a tile
// of their sphere's rectangle; a sphere wholly behind the eye gets none, and a small sphere in
// the middle of the view only a few.
TEST(ClusterGrid, ZBinsRectangleHoldsEveryPixelItsSphereCovers) {
  const FrameCamera cam = test_camera();
  const Grid g = grid_of_tiles(320, 180, 16, 1, cam.znear, cam.zfar);
  std::uint32_t state = 12345u;
  auto uniform = [&] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1u << 24);
  };
  int checked = 0;
  for (int k = 0; k < 400; ++k) {
    const glm::vec3 c((uniform() - 0.5f) * 40.f, (uniform() - 0.5f) * 20.f, -uniform() * 30.f + 1.f);
    const float r = 0.1f + uniform() * 4.f;
    const TileRect rect = sphere_tiles(cam, g, c, r);
    for (int s = 0; s < 200; ++s) {
      const float z = uniform() * 2.f - 1.f, a = uniform() * 6.2831853f, q = std::sqrt(1.f - z * z);
      const glm::vec3 p = c + r * glm::vec3(q * std::cos(a), q * std::sin(a), z);
      if (-p.z < cam.znear) continue;  // no surface is nearer than the near plane
      const glm::vec4 clip = cam.projection * glm::vec4(p, 1.f);
      const glm::vec2 px = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(g.width, g.height);
      if (px.x < 0 || px.y < 0 || px.x >= float(g.width) || px.y >= float(g.height)) continue;
      ++checked;
      ASSERT_TRUE(rect.holds(int(px.x) / g.tile_w, int(px.y) / g.tile_h))
          << "sphere " << k << " at (" << c.x << ", " << c.y << ", " << c.z << ") r " << r << ": pixel (" << px.x << ", "
          << px.y << ") outside tiles " << rect.lo.x << ".." << rect.hi.x << " x " << rect.lo.y << ".." << rect.hi.y;
    }
  }
  EXPECT_GT(checked, 10000);
  const TileRect behind = sphere_tiles(cam, g, glm::vec3(0, 0, 5), 1.f);
  EXPECT_TRUE(behind.lo.x > behind.hi.x || behind.lo.y > behind.hi.y);
  const TileRect small = sphere_tiles(cam, g, glm::vec3(0, 0, -20), 0.2f);
  EXPECT_LE((small.hi.x - small.lo.x + 1) * (small.hi.y - small.lo.y + 1), 4);
}

// The records of chapter 04's tubes (pack_cluster_lights with tubes): after every point and
// spot in light order, so that light first_tube on is a tube and the spots' cones keep their
// places; each the capsule the assignment bins (start, volume radius, end) and the tube's
// index in the tubes' own buffer, where the shading finds the rest.
#include "chapters/04_neon/capsule.h"
#include "chapters/09_clustered/clustered_lights.h"

TEST(ClusterRecords, TubesEndTheLightOrderWithTheirCapsuleAndIndex) {
  Light point{.color = {1, 1, 1}, .intensity = 2, .position = {1, 2, 3}};
  Light spot = point;
  spot.type = LightType::Spot;
  spot.direction = {0, -1, 0};
  spot.inner_cone = 0.2f;
  spot.outer_cone = 0.4f;
  ch03::LightSet set;
  set.points = {ch03::pack_point(point, 4.f), ch03::pack_point(point, 5.f)};
  set.cones = {ch03::pack_spot(spot, 6.f)};
  set.wide_spots = {ch03::pack_spot(spot, 7.f)};
  std::vector<ch04::NeonLight> tubes(3);
  std::vector<ch04::NeonGpu> packed;
  for (int k = 0; k < 3; ++k) {
    tubes[k].start = glm::vec3(k, 1, -2);
    tubes[k].end = glm::vec3(k + 0.5f, 3, -2.f - k);
    tubes[k].door_axis = glm::normalize(glm::cross(tubes[k].end - tubes[k].start, glm::vec3(1, 0, 0)));
    packed.push_back(ch04::pack_neon(tubes[k], 2.f + float(k)));
  }
  const ClusterRecords without = pack_cluster_lights(set);
  EXPECT_EQ(without.first_tube, 4) << "no tubes: the lights' count";
  const ClusterRecords r = pack_cluster_lights(set, packed);
  ASSERT_EQ(r.lights.size(), 7u);
  EXPECT_EQ(r.first_spot, 2);
  EXPECT_EQ(r.first_tube, 4);
  EXPECT_EQ(r.spots.size(), 2u) << "a cone per spot, none per tube";
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(r.lights[i].position_radius, without.lights[i].position_radius) << "light " << i;
    EXPECT_EQ(r.lights[i].radiance_inv_range2, without.lights[i].radiance_inv_range2) << "light " << i;
  }
  for (int k = 0; k < 3; ++k) {
    const ClusterRecords::Light& t = r.lights[std::size_t(r.first_tube + k)];
    // pack_neon keeps the ends in a matrix: rounding, a few ulps of the coordinates.
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(t.position_radius[c], tubes[k].start[c], 1e-5f) << "tube " << k << " start";
      EXPECT_NEAR(t.radiance_inv_range2[c], tubes[k].end[c], 1e-5f) << "tube " << k << " end";
    }
    EXPECT_FLOAT_EQ(t.position_radius.w, 2.f + float(k)) << "tube " << k << ": its volume radius, the cut";
    EXPECT_EQ(t.radiance_inv_range2.w, float(k)) << "tube " << k << ": its index";
  }
}
