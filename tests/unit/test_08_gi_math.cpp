// Chapter 08's maths without OpenGL: the disk-to-disk transfer term (finite as r -> 0, zero for
// emitters behind the receiver or facing away, exact on the axis, reciprocal for equal disks),
// the sampling patterns (inside the disk, an equal share of its area each), and the truth's
// direct light (chapter 03's cut).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "chapters/08_ssgi/gi_math.h"
#include "chapters/08_ssgi/gi_truth.h"
#include "chapters/08_ssgi/guard_band.h"
#include "common/error.h"

#include <glm/gtc/matrix_transform.hpp>

using namespace lp;
using namespace lp::ch08;

namespace {
constexpr float kPi = 3.14159265358979f;
const glm::vec3 kUp(0, 1, 0), kDown(0, -1, 0);
}  // namespace

// On the axis, a disk of radius a at distance r covers sin^2 of the cone's half-angle of the
// receiver's projected hemisphere: a^2 / (r^2 + a^2), the exact form factor (float rounding: 1e-6).
TEST(Transfer, ExactForADiskOnTheAxis) {
  for (float a : {0.01f, 0.3f, 1.f, 4.f})
    for (float r : {0.05f, 1.f, 7.f}) {
      float area = kPi * a * a;
      EXPECT_NEAR(disk_transfer(glm::vec3(0), kUp, glm::vec3(0, r, 0), kDown, area), a * a / (r * r + a * a), 1e-6f)
          << "a " << a << " r " << r;
    }
}

// The +A: as the emitter comes to the receiver the transfer tends to cos cos (here 1), never
// infinity; at exactly r = 0 there is no direction and it is 0, not NaN.
TEST(Transfer, FiniteAsTheDistanceGoesToZero) {
  float previous = 0.f;
  for (float r = 1.f; r > 1e-6f; r *= 0.1f) {
    float f = disk_transfer(glm::vec3(0), kUp, glm::vec3(0, r, 0), kDown, 0.01f);
    EXPECT_TRUE(std::isfinite(f));
    EXPECT_LE(f, 1.f);
    EXPECT_GE(f, previous);  // grows as the emitter comes closer ...
    previous = f;
  }
  EXPECT_GT(previous, 0.999f);  // ... to 1
  EXPECT_EQ(disk_transfer(glm::vec3(0), kUp, glm::vec3(0), kDown, 0.01f), 0.f);
}

TEST(Transfer, ZeroForAnEmitterBehindTheReceiver) {
  // below the receiver's tangent plane, whichever way it faces
  EXPECT_EQ(disk_transfer(glm::vec3(0), kUp, glm::vec3(0.3f, -1, 0), kUp, 0.5f), 0.f);
  EXPECT_EQ(disk_transfer(glm::vec3(0), kUp, glm::vec3(0.3f, -1, 0), kDown, 0.5f), 0.f);
  // in the tangent plane
  EXPECT_EQ(disk_transfer(glm::vec3(0), kUp, glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0), 0.5f), 0.f);
}

TEST(Transfer, ZeroForAnEmitterFacingAway) {
  // above the receiver, its lit side turned up, away from it
  EXPECT_EQ(disk_transfer(glm::vec3(0), kUp, glm::vec3(0.2f, 1, 0), kUp, 0.5f), 0.f);
  // edge on
  EXPECT_EQ(disk_transfer(glm::vec3(0), kUp, glm::vec3(0, 1, 0), glm::vec3(1, 0, 0), 0.5f), 0.f);
  // and the same emitter turned to the receiver sends light
  EXPECT_GT(disk_transfer(glm::vec3(0), kUp, glm::vec3(0.2f, 1, 0), kDown, 0.5f), 0.f);
}

// A_p F(p <- e) = A_e F(e <- p): exact for two disks of the same area (both denominators are
// pi r^2 + A), and off by the ratio (pi r^2 + A_p) / (pi r^2 + A_e) otherwise.
TEST(Transfer, ReciprocalForEqualAreasAndOffByTheStatedRatioOtherwise) {
  const glm::vec3 p(0.1f, 0.f, -0.2f), np = glm::normalize(glm::vec3(0.2f, 1.f, 0.1f));
  const glm::vec3 e(0.6f, 0.9f, 0.3f), ne = glm::normalize(glm::vec3(-0.5f, -1.f, 0.2f));
  const float r2 = glm::dot(e - p, e - p);
  for (float area : {0.01f, 0.2f, 1.5f}) {
    float forward = area * disk_transfer(p, np, e, ne, area), back = area * disk_transfer(e, ne, p, np, area);
    EXPECT_GT(forward, 0.f);
    EXPECT_NEAR(forward, back, 1e-6f * forward);
  }
  const float ap = 0.05f, ae = 0.8f;
  float forward = ap * disk_transfer(p, np, e, ne, ae), back = ae * disk_transfer(e, ne, p, np, ap);
  EXPECT_NEAR(back / forward, (kPi * r2 + ae) / (kPi * r2 + ap), 1e-5f);
  EXPECT_GT(std::abs(back / forward - 1.f), 0.05f);  // not reciprocal: the +A differs
}

TEST(Transfer, ZeroForNoArea) {
  EXPECT_EQ(disk_transfer(glm::vec3(0), kUp, glm::vec3(0, 1, 0), kDown, 0.f), 0.f);
  EXPECT_EQ(disk_transfer(glm::vec3(0), kUp, glm::vec3(0, 1, 0), kDown, std::nanf("")), 0.f);
}

// [patterns-cover]
// Every pattern's points lie in the unit disk, and each of 4 rings of equal area x 4 quadrants
// (16 cells of area pi / 16) holds its share of n points: within 2 of n / 16 for the spiral and
// the randomised pattern at n = 64, 128 (a pattern that crowds the centre, as r = i / n would,
// puts n / 4 in the inner ring and fails); for the randomised one at several pixels.
TEST(Patterns, InsideTheDiskWithAnEqualShareOfItsArea) {
  for (Pattern pattern : {Pattern::Spiral, Pattern::Randomised})
    for (int n : {64, 128})
      for (glm::uvec2 pixel : {glm::uvec2(0), glm::uvec2(17, 3), glm::uvec2(1919, 1079)}) {
        int cells[16] = {};
        for (int i = 0; i < n; ++i) {
          glm::vec2 q = pattern_point(pattern, i, n, pixel);
          float r = glm::length(q);
          ASSERT_LE(r, 1.f + 1e-6f);
          int ring = std::min(3, int(r * r * 4.f));
          int quadrant = (q.x >= 0 ? 0 : 1) + (q.y >= 0 ? 0 : 2);
          ++cells[ring * 4 + quadrant];
        }
        for (int c = 0; c < 16; ++c)
          EXPECT_NEAR(cells[c], n / 16.0, 2.0) << kPatternNames[int(pattern)] << " n " << n << " cell " << c;
      }
}
// [/patterns-cover]

// The regular grid: rings x spokes points (16: 4 x 4), the same directions on every ring, each
// ring an equal area: its points at sqrt((k + 0.5) / rings).
TEST(Patterns, RegularIsAPolarGridOfEqualAreas) {
  EXPECT_EQ(regular_rings(16), 4);
  EXPECT_EQ(regular_rings(15), 3);
  EXPECT_EQ(regular_rings(1), 1);
  for (int i = 0; i < 16; ++i) {
    glm::vec2 q = pattern_point(Pattern::Regular, i, 16);
    EXPECT_NEAR(glm::length(q), std::sqrt((float(i / 4) + 0.5f) / 4.f), 1e-6f);
    glm::vec2 first = pattern_point(Pattern::Regular, i % 4, 16);
    EXPECT_NEAR(glm::dot(glm::normalize(q), glm::normalize(first)), 1.f, 1e-6f);  // the same spoke
  }
}

TEST(Patterns, RandomisedChangesFromPixelToPixelSpiralDoesNot) {
  EXPECT_EQ(pattern_point(Pattern::Spiral, 5, 16, glm::uvec2(1, 2)), pattern_point(Pattern::Spiral, 5, 16, glm::uvec2(9, 4)));
  EXPECT_NE(pattern_point(Pattern::Randomised, 5, 16, glm::uvec2(1, 2)),
            pattern_point(Pattern::Randomised, 5, 16, glm::uvec2(9, 4)));
  glm::vec2 j = pixel_jitter(glm::uvec2(123, 456));
  EXPECT_GE(j.x, 0.f);
  EXPECT_LT(j.x, 1.f);
  EXPECT_GE(j.y, 0.f);
  EXPECT_LT(j.y, 1.f);
}

// The truth's direct light ends at chapter 03's cut, as the light shader's does, and follows
// chapter 01's attenuation inside it.
TEST(DirectLight, EndsAtTheCut) {
  ch03::LightSet set;
  ch03::PointInstance p{};
  p.position_radius = glm::vec4(0, 2, 0, 1.5f);
  p.radiance_range = glm::vec4(1, 1, 1, 0);
  set.points.push_back(p);
  const DirectLightSet d = direct_lights(set);
  auto none = [](int, glm::vec3, float) { return false; };
  glm::vec3 inside = direct_diffuse(d, glm::vec3(0, 1, 0), kUp, none);   // 1 below the light
  glm::vec3 outside = direct_diffuse(d, glm::vec3(0, 0, 0), kUp, none);  // 2 below: past the cut
  EXPECT_NEAR(inside.x, 1.f, 1e-5f);  // 1 / d^2, n . l = 1
  EXPECT_EQ(outside.x, 0.f);
  // facing away: nothing
  EXPECT_EQ(direct_diffuse(d, glm::vec3(0, 1, 0), kDown, none).x, 0.f);
  // a shadowed light gives nothing
  EXPECT_EQ(direct_diffuse(d, glm::vec3(0, 1, 0), kUp, [](int, glm::vec3, float) { return true; }).x, 0.f);
}

TEST(GiErrors, CapturedIsTheEnergyRatio) {
  ImageF truth = ImageF::blank(2, 1, 3), estimate = ImageF::blank(2, 1, 3);
  for (float& v : truth.data) v = 0.2f;
  for (float& v : estimate.data) v = 0.1f;
  for (int c = 0; c < 3; ++c) truth.at(1, 0, c) = kTruthSky;  // the sky is not counted
  GiErrors e = gi_errors(estimate, truth);
  EXPECT_EQ(e.pixels, 1);
  EXPECT_NEAR(e.captured, 0.5, 1e-6);
  EXPECT_NEAR(e.mean_abs, 0.1, 1e-6);
  EXPECT_NEAR(e.relative, 0.5, 1e-6);
}

// --guard-band: below 1 a fraction of the screen's height, from 1 on pixels (rounded), bounded.
TEST(GuardBand, OptionIsAFractionBelowOneAndPixelsFromOne) {
  EXPECT_EQ(guard_band_pixels(0.0, 180), 0);
  EXPECT_EQ(guard_band_pixels(0.1, 180), 18);
  EXPECT_EQ(guard_band_pixels(0.25, 90), 23);  // 22.5 rounds up
  EXPECT_EQ(guard_band_pixels(1.0, 180), 1);
  EXPECT_EQ(guard_band_pixels(24.4, 180), 24);
  EXPECT_EQ(guard_band_pixels(kMaxGuardBand, 180), kMaxGuardBand);
  EXPECT_THROW(guard_band_pixels(kMaxGuardBand + 1, 180), Error);
  EXPECT_THROW(guard_band_pixels(-1.0, 180), Error);
  EXPECT_THROW(guard_band_pixels(std::nan(""), 180), Error);
}

// The wide camera keeps every screen pixel's ray: a point the screen's camera projects to the
// centre of pixel (x, y) projects to the centre of (x + g, y + g) of the wide frame, to float
// rounding (1e-3 pixel).
TEST(GuardBand, WideCameraKeepsEveryScreenPixelsRay) {
  const int w = 320, h = 180, g = 18;
  FrameCamera cam;
  cam.yfov = 0.6864f;
  cam.aspect = float(w) / h;
  cam.projection = glm::perspective(cam.yfov, cam.aspect, 0.05f, 20.f);
  cam.view = glm::lookAt(glm::vec3(0.3f, 1.f, 3.f), glm::vec3(0.f, 0.8f, 0.f), glm::vec3(0, 1, 0));
  const GuardBand band{g};
  const FrameCamera wide = band.widen(cam, w, h);
  const glm::mat4 to_world = glm::inverse(cam.projection * cam.view);
  for (glm::vec2 px : {glm::vec2(0.5f, 0.5f), glm::vec2(319.5f, 179.5f), glm::vec2(100.5f, 40.5f), glm::vec2(160.f, 90.f)}) {
    const glm::vec4 ndc((px.x / w) * 2.f - 1.f, (px.y / h) * 2.f - 1.f, 0.3f, 1.f);
    glm::vec4 world = to_world * ndc;
    world /= world.w;
    const glm::vec4 clip = wide.projection * wide.view * world;
    const glm::vec2 at((clip.x / clip.w * 0.5f + 0.5f) * band.width(w), (clip.y / clip.w * 0.5f + 0.5f) * band.height(h));
    EXPECT_NEAR(at.x, px.x + g, 1e-3f);
    EXPECT_NEAR(at.y, px.y + g, 1e-3f);
  }
  EXPECT_NEAR(std::tan(wide.yfov / 2.f), std::tan(cam.yfov / 2.f) * float(h + 2 * g) / h, 1e-6f);
  EXPECT_EQ(GuardBand{0}.widen(cam, w, h).projection, cam.projection);  // no band: the screen's camera
}
