// Chapter 05's maths on the CPU: the tonemapping curves, eye adaptation, the policy for
// NaN / Inf / overflow, the exact log-average and the naive mip chain's coverage, the
// bright pass and the reference bloom. Every bound is stated where it is used.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numeric>

#include "chapters/05_hdr/exposure_feedback.h"
#include "chapters/05_hdr/hdr_math.h"
#include "chapters/05_hdr/reference.h"

using namespace lp;
using namespace lp::ch05;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
const Operator kOperators[] = {Operator::Clamp, Operator::Reinhard, Operator::ReinhardExtended, Operator::Aces};

// 10^-6 .. 10^6, 200 points per decade.
std::vector<float> log_grid() {
  std::vector<float> xs;
  for (int i = -1200; i <= 1200; ++i) xs.push_back(std::pow(10.f, float(i) / 200.f));
  return xs;
}


}  // namespace

// --- Tonemapping operators ---------------------------------------------------------------

TEST(Operators, BlackStaysBlack) {
  for (Operator op : kOperators) EXPECT_EQ(tonemap(op, 0.f, 4.f), 0.f) << int(op);
}

TEST(Operators, AreMonotonicAndStayInTheDisplayRange) {
  for (Operator op : kOperators) {
    float previous = 0.f;
    for (float x : log_grid()) {
      float y = tonemap(op, x, 4.f);
      EXPECT_GE(y, previous) << "operator " << int(op) << " decreases at x = " << x;
      EXPECT_GE(y, 0.f);
      EXPECT_LE(y, 1.f);
      previous = y;
    }
  }
}

TEST(Operators, ReinhardHalvesOneAndNeverReachesWhite) {
  EXPECT_FLOAT_EQ(tonemap_reinhard(1.f), 0.5f);
  // 1 - x / (1 + x) = 1 / (1 + x): the distance to white falls like 1/x and is never 0
  // below 2^24, where 1 + x stops being representable apart from x.
  for (float x : {10.f, 1e3f, 1e6f}) {
    EXPECT_LT(tonemap_reinhard(x), 1.f);
    EXPECT_NEAR(1.f - tonemap_reinhard(x), 1.f / (1.f + x), 2e-7f) << x;  // one float ulp near 1
  }
  // Slope 1 at black: dark values pass through unchanged.
  EXPECT_NEAR(tonemap_reinhard(1e-4f) / 1e-4f, 1.f, 2e-4f);
}

TEST(Operators, ExtendedReinhardMapsTheWhitePointToOne) {
  for (float white : {0.5f, 1.f, 4.f, 11.2f, 1000.f}) {
    // x (1 + x / W^2) / (1 + x) at x = W is (W + 1) / (1 + W) = 1, up to float rounding of
    // four operations (4 ulp at 1 = 4.8e-7).
    EXPECT_NEAR(tonemap_reinhard_extended(white, white), 1.f, 4.8e-7f) << white;
    EXPECT_LT(tonemap_reinhard_extended(0.9f * white, white), 1.f);
    EXPECT_EQ(tonemap_reinhard_extended(2.f * white, white), 1.f);  // burnt out above W
  }
  // As W grows it becomes plain Reinhard: the difference is x^2 / (W^2 (1 + x)).
  for (float x : {0.1f, 1.f, 10.f}) EXPECT_NEAR(tonemap_reinhard_extended(x, 1e4f), tonemap_reinhard(x), 1e-6f);
}

TEST(Operators, AcesToeShoulderAndSaturation) {
  // f(x) = x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14) reaches 1 where
  // 0.08 x^2 - 0.56 x - 0.14 = 0, x = (0.56 + sqrt(0.56^2 + 4 * 0.08 * 0.14)) / 0.16.
  double saturation = (0.56 + std::sqrt(0.56 * 0.56 + 4 * 0.08 * 0.14)) / 0.16;
  EXPECT_NEAR(saturation, 7.24166, 1e-5);
  EXPECT_LT(tonemap_aces(float(saturation) * 0.999f), 1.f);
  EXPECT_EQ(tonemap_aces(float(saturation) * 1.001f), 1.f);
  // Toe: darker than Reinhard near black (slope 0.03 / 0.14 at 0), brighter in the middle.
  EXPECT_NEAR(tonemap_aces(1e-5f) / 1e-5f, 0.03 / 0.14, 1e-3);
  EXPECT_LT(tonemap_aces(0.01f), tonemap_reinhard(0.01f));
  EXPECT_GT(tonemap_aces(0.18f), tonemap_reinhard(0.18f));
}

TEST(Operators, ClampIsTheIdentityBelowOne) {
  for (float x : {0.f, 0.25f, 0.5f, 1.f}) EXPECT_EQ(tonemap_clamp(x), x);
  EXPECT_EQ(tonemap_clamp(3.f), 1.f);
}

// --- Eye adaptation ----------------------------------------------------------------------

TEST(Adaptation, TauZeroAdaptsAtOnce) { EXPECT_EQ(adapt(5.f, 0.1f, 1.f / 60.f, 0.f), 0.1f); }

TEST(Adaptation, CoversOneMinusOneOverEAfterTau) {
  const float tau = 0.5f, dt = tau / 100.f;
  float a = 1.f;
  for (int i = 0; i < 100; ++i) a = adapt(a, 2.f, dt, tau);
  // 100 float steps: each rounds by at most ~2 ulp of ~1.5 (2.4e-7); the errors shrink by
  // exp(-dt/tau) every step, so they sum to well under 100 x 2.4e-7 = 2.4e-5.
  EXPECT_NEAR(a, 1.f + (1.f - std::exp(-1.f)), 2.4e-5f);
}

TEST(Adaptation, DoesNotDependOnTheFrameRate) {
  const float tau = 0.3f;
  float at60 = 10.f, at30 = 10.f;
  for (int i = 0; i < 60; ++i) at60 = adapt(at60, 0.5f, 1.f / 60.f, tau);
  for (int i = 0; i < 30; ++i) at30 = adapt(at30, 0.5f, 1.f / 30.f, tau);
  // Exactly equal in real arithmetic; 60 float steps of values <= 10 differ by < 60 x 2 ulp.
  EXPECT_NEAR(at60, at30, 60 * 2 * 9.6e-7f);
}

TEST(Adaptation, ApproachesWithoutOvershootFromBothSides) {
  for (float start : {0.01f, 100.f}) {
    float a = start, target = 1.f;
    for (int i = 0; i < 2000; ++i) {
      float next = adapt(a, target, 1.f / 60.f, 0.5f);
      if (start < target) { EXPECT_GE(next, a); EXPECT_LE(next, target); }
      else { EXPECT_LE(next, a); EXPECT_GE(next, target); }
      a = next;
    }
    // 2000 frames = 67 tau: exp(-67) of the gap is gone in real arithmetic. In float the
    // steps stop once (a - target) k, with k = 1 - exp(-dt / tau) = 0.0328, is below half an
    // ulp of 1 (6e-8): a stays within 6e-8 / 0.0328 = 1.82e-6 of the target, from above.
    EXPECT_NEAR(a, target, 1.82e-6f);
  }
}

// --- How far a light may be cut: the curve's slope and the exposure's bound ----------------

TEST(OutputSlope, TheSlopesAreTheCurvesDerivatives) {
  // Central differences of the float curves, where they are smooth (away from the clamps).
  for (Operator op : kOperators)
    for (double x : {1e-3, 0.01, 0.1, 0.5, 0.9, 2.0, 3.0}) {
      const double h = 1e-3 * x;
      const double numeric = (double(tonemap(op, float(x + h), 4.f)) - tonemap(op, float(x - h), 4.f)) / (2 * h);
      EXPECT_NEAR(tonemap_slope(op, x, 4.0), numeric, 2e-3 * std::max(1.0, numeric) + 2e-4 / x) << kOperatorNames[int(op)] << " at " << x;
    }
}

TEST(OutputSlope, IsTheSteepestPointOfCurveAndEncoding) {
  // Reinhard, clamp and extended Reinhard are steepest at black with slope 1 (and sRGB is):
  // 1, plus the search's 10^-3. ACES's toe is flat; its steepest output point is where the
  // curve leaves sRGB's linear segment.
  EXPECT_NEAR(output_slope(Operator::Reinhard, 4.f), 1.001f, 1e-6f);
  EXPECT_NEAR(output_slope(Operator::Clamp, 4.f), 1.001f, 1e-6f);
  EXPECT_NEAR(output_slope(Operator::ReinhardExtended, 4.f), 1.001f, 1e-6f);
  EXPECT_NEAR(output_slope(Operator::Aces, 4.f), 0.4952f * 1.001f, 1e-4f);  // T'(0.00876)
  // No point of a grid ten times finer (2000 a decade) is steeper than the bound, and the
  // bound is no more than 0.2 % above the steepest point found.
  for (Operator op : kOperators)
    for (float white : {0.5f, 4.f}) {
      double steepest = 0;
      for (int i = -7 * 2000; i <= 3 * 2000; ++i) {
        const double x = std::pow(10.0, i / 2000.0);
        steepest = std::max(steepest, srgb_encode_slope(tonemap(op, float(x), white)) * tonemap_slope(op, x, white) / 12.92);
      }
      EXPECT_LE(steepest, output_slope(op, white)) << kOperatorNames[int(op)] << " white " << white;
      EXPECT_GE(steepest, output_slope(op, white) / 1.002) << kOperatorNames[int(op)] << " white " << white;
    }
}

TEST(Exposure, TheFloorStopsTheEyeInTheDark) {
  // Above the floor the exposure is the fixed key's, key / adapted; below it, key / floor:
  // the exposed log-average (exposure x adapted) falls with the scene, key x adapted / floor.
  EXPECT_FLOAT_EQ(exposure_for(0.18f, 2.f, 0.18f), 0.18f / 2.f);
  EXPECT_FLOAT_EQ(exposure_for(0.18f, 0.045f, 0.18f), 1.f);
  EXPECT_FLOAT_EQ(exposure_for(0.18f, 0.045f, 0.f), 4.f) << "no floor: the fixed key at any light";
  EXPECT_FLOAT_EQ(exposure_for(0.18f, 0.045f, 0.09f) * 0.045f, 0.09f) << "half the floor: shown a stop below the key";
}

TEST(ExposureBound, HoldsForAnySequenceOfFrames) {
  // Eyes adapting to random frames (black ones included), at random frame times and time
  // constants: the exposure of every later frame is within the bound from every earlier one,
  // and never above the stage's limit; every other run with an adaptation floor.
  std::uint32_t seed = 12345;
  auto uniform = [&] { seed = seed * 1664525u + 1013904223u; return float(seed >> 8) / 16777216.f; };
  const float key = 0.18f, delta = 1e-4f;
  for (int run = 0; run < 50; ++run) {
    const float start = std::pow(10.f, -2.f + 4.f * uniform());
    const AdaptationSettings s{.key = key, .adapt_floor = run % 2 ? std::pow(10.f, -3.f + 3.f * uniform()) : 0.f};
    std::vector<float> adapted, decay;
    float a = 0, sum = 0;
    for (int n = 0; n < 200; ++n) {
      const float target = uniform() < 0.2f ? delta : delta + std::pow(10.f, -4.f + 8.f * uniform());  // exp(mean log(delta + L)) >= delta
      const float dt = 0.002f + 0.1f * uniform(), tau = 0.05f + 2.f * uniform();
      a = n == 0 ? target * start : adapt(a, target, dt, tau);
      sum += n == 0 ? 0.f : dt / tau;
      adapted.push_back(a);
      decay.push_back(sum);
      const float exposure = exposure_for(key, a, s.adapt_floor);
      ASSERT_LE(exposure, exposure_limit(s, delta, start)) << "run " << run << " frame " << n;
      for (int m = std::max(0, n - 8); m < n; ++m)
        ASSERT_LE(exposure, exposure_bound_after(s, adapted[m], double(decay[n]) - decay[m], std::uint64_t(n - m)))
            << "run " << run << " frame " << n << " from " << m;
    }
  }
}

// --- What the stage does with values a radiance buffer should not hold -----------------

TEST(Sanitize, Policy) {
  EXPECT_FALSE(sanitize({kNaN, 1, 1}).valid);
  EXPECT_EQ(sanitize({1, kNaN, 1}).rgb, glm::vec3(0));
  EXPECT_EQ(sanitize({kInf, 1, 2}).rgb, glm::vec3(kHalfMax, 1, 2));
  EXPECT_EQ(sanitize({1e5f, 1e9f, 65504.f}).rgb, glm::vec3(kHalfMax));
  EXPECT_EQ(sanitize({-1.f, -kInf, 0.25f}).rgb, glm::vec3(0, 0, 0.25f));
  EXPECT_TRUE(sanitize({-kInf, kInf, 0}).valid);
}

// --- The exact log-average (the ground truth) ---------------------------------------------

TEST(ExactLogAverage, BlackFrameAveragesToDelta) {
  ExactLogAverage r = exact_log_average(constant_image(17, 9, glm::vec3(0)), 1e-4f);
  EXPECT_EQ(r.count, 17u * 9u);
  EXPECT_NEAR(r.luminance / double(1e-4f), 1.0, 1e-12);
}

TEST(ExactLogAverage, IsTheGeometricMean) {
  // Half the pixels at luminance 0.01, half at 100: the log-average is
  // sqrt((delta + 0.01) (delta + 100)), about 1, however bright the bright half is.
  ImageF img = constant_image(10, 4, glm::vec3(0.01f));
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 10; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = 100.f;
  const double d = 1e-4f;
  double expected = std::sqrt((d + double(0.01f) * (0.2126 + 0.7152 + 0.0722)) * (d + 100.0 * (0.2126 + 0.7152 + 0.0722)));
  EXPECT_NEAR(exact_log_average(img, 1e-4f).luminance / expected, 1.0, 1e-12);
}

TEST(ExactLogAverage, FollowsThePolicy) {
  ImageF img = constant_image(4, 4, glm::vec3(0.5f));
  img.at(0, 0, 1) = kNaN;  // left out
  img.at(1, 0, 0) = kInf;  // 65504 in red
  img.at(2, 0, 2) = -3.f;  // 0 in blue
  ExactLogAverage r = exact_log_average(img, 1e-4f);
  EXPECT_EQ(r.count, 15u);
  double d = 1e-4f;
  double sum = 13 * std::log(d + 0.5) + std::log(d + 0.2126 * 65504.0 + 0.7152 * 0.5 + 0.0722 * 0.5) +
               std::log(d + 0.2126 * 0.5 + 0.7152 * 0.5);
  EXPECT_NEAR(r.mean_log, sum / 15, 1e-12);
}

TEST(NaiveChain, KeepsOnlyTheLargestPowerOfTwoCorner) {
  // 1920 -> 1024 columns and 1080 -> 1024 rows reach the 1x1 level: 49.4% of the pixels
  // of a 1080p frame never take part in the "average".
  EXPECT_EQ(naive_chain_pixels(1920, 1080), 1024u * 1024u);
  EXPECT_NEAR(1.0 - double(naive_chain_pixels(1920, 1080)) / (1920.0 * 1080.0), 0.4943, 1e-4);
  EXPECT_EQ(naive_chain_pixels(1024, 1024), 1024u * 1024u);  // powers of two lose nothing
  EXPECT_EQ(naive_chain_pixels(1, 1080), 1024u);
  EXPECT_EQ(naive_chain_pixels(1, 1), 1u);
  EXPECT_EQ(naive_chain_pixels(321, 181), 256u * 128u);  // 43.6% lost
}

// --- Bloom --------------------------------------------------------------------------------

TEST(BrightPass, KeepsTheExcessWithItsColourUpToTheLimit) {
  EXPECT_EQ(bright_pass(glm::vec3(0.9f), 1.f, 64.f), glm::vec3(0));
  glm::vec3 c(3.f, 1.5f, 0.75f);
  glm::vec3 b = bright_pass(c, 1.f, 64.f);
  EXPECT_NEAR(luminance(b), luminance(c) - 1.f, 1e-6f);
  EXPECT_NEAR(b.r / b.g, 2.f, 1e-6f);  // same hue
  EXPECT_NEAR(luminance(bright_pass(glm::vec3(1e4f), 1.f, 64.f)), 64.f, 1e-3f);
  EXPECT_EQ(bright_pass(glm::vec3(0), 0.f, 64.f), glm::vec3(0));  // no 0/0 at threshold 0
}

TEST(ReferenceBloom, ConservesEnergyAwayFromTheEdges) {
  ImageF img = constant_image(64, 48, glm::vec3(0));
  for (int c = 0; c < 3; ++c) img.at(30, 20, c) = 10.f;
  ImageF bloom = reference_bloom(img, 1.f, 1.f, 64.f, 3.f);  // radius ceil(9) < 20 from every edge
  double sum = std::accumulate(bloom.data.begin(), bloom.data.end(), 0.0);
  EXPECT_NEAR(sum, 3 * 9.0, 27 * 1e-6);  // float storage of the result: ~1e-7 per value
  EXPECT_NEAR(bloom.at(29, 20, 0), bloom.at(31, 20, 0), 1e-7);  // symmetric
  EXPECT_GT(bloom.at(30, 20, 0), bloom.at(33, 20, 0));
}
