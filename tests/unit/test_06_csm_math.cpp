// Chapter 06's convolution shadow maps (csm_math.h) without OpenGL: the truncated Fourier series
// against the step it approximates.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "chapters/06_shadows/csm_math.h"
#include "common/error.h"

using namespace lp::ch06;

namespace {
// The squared L2 distance of the truncated series from the step over (-1, 1), by the midpoint
// rule on n cells (the step's jumps at 0 and +-1 fall on cell edges).
double l2_squared(int terms, int n = 200000) {
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double x = -1.0 + (i + 0.5) * 2.0 / n;
    const double e = double(csm_step(float(x), terms)) - (x > 0 ? 1.0 : 0.0);
    sum += e * e;
  }
  return sum * 2.0 / n;
}
}  // namespace

// More terms, nearer the step: the squared L2 error is Parseval's tail (the series is the step's
// projection on its first sines), so it falls as 1 / terms. Tolerance: the midpoint rule's error
// on the ringing (cells of 1e-5 against wiggles of 1 / (2 terms)) and float sines, both well below
// a thousandth of the smallest tail here.
TEST(CsmMath, TheTruncatedSeriesApproachesTheStepAsTermsGrow) {
  double last = 1e9;
  for (int terms = 1; terms <= kMaxCsmTerms; ++terms) {
    const double measured = l2_squared(terms), parseval = csm_l2_error_squared(terms);
    EXPECT_NEAR(measured, parseval, 1e-3 * parseval) << terms << " terms";
    EXPECT_LT(measured, last) << terms << " terms";
    last = measured;
  }
  // Away from the edges (|x| in [0.25, 0.75]) the series converges pointwise: the error there
  // is bounded by the tail's sum of 2 / (c_k |sin| ...) (Dirichlet's kernel): at 8 terms, within
  // 1 / (pi terms sin(pi / 4)) of the step.
  for (float x = 0.25f; x <= 0.75f; x += 0.01f) {
    const float bound = 1.f / (3.14159265f * kMaxCsmTerms * std::sin(3.14159265f * 0.25f));
    EXPECT_NEAR(csm_step(x, kMaxCsmTerms), 1.f, bound) << x;
    EXPECT_NEAR(csm_step(-x, kMaxCsmTerms), 0.f, bound) << -x;
  }
}

// Gibbs: near the step the series overshoots, and the overshoot falls towards the
// Wilbraham-Gibbs constant, (1 / pi) Si(pi) - 1/2 = 0.08949 of the jump, never below it, as the
// count grows; the first peak lies at x = 1 / (2 terms): more terms move the ringing closer to
// the edge, never remove it.
TEST(CsmMath, TheSeriesRingsNearTheEdgeWhateverTheCount) {
  const float gibbs = 0.08949f;
  float last = 1.f;
  for (int terms = 1; terms <= kMaxCsmTerms; ++terms) {
    float peak = 0.f, at = 0.f;
    for (int i = 1; i < 20000; ++i) {
      const float x = float(i) / 40000.f;  // (0, 0.5)
      if (const float v = csm_step(x, terms); v > peak) peak = v, at = x;
    }
    std::printf("%d terms: overshoot %.5f at x = %.5f\n", terms, peak - 1.f, at);
    EXPECT_GT(peak - 1.f, gibbs - 1e-5f) << terms;  // the overshoot does not vanish with more terms
    EXPECT_LE(peak - 1.f, last) << terms;           // it falls towards the constant
    last = peak - 1.f;
    // The peak is flat, so float sines move its argmax by a few grid steps: within a twentieth
    // of the ringing's half-period 1 / (2 terms) tells it from the next wiggle.
    EXPECT_NEAR(at, 1.f / (2.f * float(terms)), 1.f / (40.f * float(terms))) << terms;
    // And under the step's other side, the mirror: an undershoot below 0 (a receiver just behind
    // its occluder reads more than fully shadowed, clamped to 0 by the lookup).
    EXPECT_NEAR(csm_step(-at, terms), 1.f - peak, 1e-5f) << terms;
  }
}

// The map's values may be filtered: the reconstruction is linear in them, so the lookup of the
// averaged basis is the average of the lookups (before the doubling and the clamp), and with one
// depth it is the truncated step itself.
TEST(CsmMath, FilteringTheBasisAveragesTheReconstructedSteps) {
  const int terms = 4;
  const std::vector<float> depths = {0.2f, 0.35f, 0.8f};
  std::vector<float> average(2 * terms, 0.f);
  for (float z : depths) {
    const std::vector<float> b = csm_basis(z, terms);
    for (int i = 0; i < 2 * terms; ++i) average[std::size_t(i)] += b[std::size_t(i)] / float(depths.size());
  }
  for (float d = 0.05f; d < 1.f; d += 0.05f) {
    float expected = 0.f;
    for (float z : depths) expected += csm_step(z - d, terms) / float(depths.size());
    // Float sines and sums: a few ulps of terms of order 1.
    EXPECT_NEAR(csm_visibility(average, d, terms), std::clamp(2.f * expected, 0.f, 1.f), 2e-5f) << d;
    EXPECT_NEAR(csm_visibility(csm_basis(0.5f, terms), d, terms), std::clamp(2.f * csm_step(0.5f - d, terms), 0.f, 1.f),
                2e-5f) << d;
  }
  EXPECT_THROW(csm_step(0.f, 0), lp::Error);
  EXPECT_THROW(csm_step(0.f, kMaxCsmTerms + 1), lp::Error);
}
