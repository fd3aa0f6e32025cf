// Chapter 07's maths without OpenGL (ao_math.h): the kernels, the noise reflection, the disk
// terms' limits and the blur's similarity weight.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "chapters/07_ssao/ao_math.h"
#include "chapters/07_ssao/ao_truth.h"
#include "common/rng.h"

using namespace lp;
using namespace lp::ch07;

namespace {
constexpr float kPi = 3.14159265358979f;
}

TEST(Kernel, RandomKernelStaysInTheHemisphereAndCoversIt) {
  auto k = random_kernel(64, 1);
  ASSERT_EQ(k.size(), 64u);
  int octant[4] = {0, 0, 0, 0};  // every quarter of azimuth is sampled
  for (auto p : k) {
    EXPECT_TRUE(in_kernel_hemisphere(p)) << p.x << ' ' << p.y << ' ' << p.z;
    octant[(p.x >= 0) + 2 * (p.y >= 0)]++;
  }
  // 64 points, a quarter each expected (16): a binomial(64, 1/4) is below 6 with p < 1e-3
  for (int q : octant) EXPECT_GE(q, 6);
  // lengths grow as (i / N)^2 from kMinLength: the first is the shortest, the last near 1
  EXPECT_NEAR(glm::length(k.front()), kMinLength, 1e-5f);
  EXPECT_GT(glm::length(k.back()), 0.9f);
}

TEST(Kernel, EnergyMinimisedSpacingGrowsAndStaysInTheHemisphere) {
  std::vector<float> spacing;
  auto k = energy_minimised_kernel(32, 3, 100, &spacing);
  ASSERT_EQ(spacing.size(), 101u);  // the start and each of 100 iterations
  for (auto p : k) EXPECT_TRUE(in_kernel_hemisphere(p)) << p.x << ' ' << p.y << ' ' << p.z;
  // the springs push the closest pair apart: after relaxing, the minimum spacing is at least
  // twice the random kernel's (random points cluster; relaxed ones approach the rest length)
  EXPECT_GT(spacing.back(), 2.f * spacing.front());
  EXPECT_GT(spacing[50], spacing.front());
}

TEST(Noise, ReflectionKeepsTheHemisphereAboutTheNormal) {
  auto noise = noise_tile(5);
  ASSERT_EQ(noise.size(), 16u);
  auto k = energy_minimised_kernel(16, 2);
  for (auto r : noise) {
    EXPECT_NEAR(glm::length(r), 1.f, 1e-5f);
    EXPECT_EQ(r.z, 0.f);
    for (auto p : k) {
      glm::vec3 q = reflect_about(p, r);
      EXPECT_NEAR(q.z, p.z, 1e-6f);                          // the height above the surface
      EXPECT_NEAR(glm::length(q), glm::length(p), 1e-5f);    // and the distance stay
      EXPECT_TRUE(in_kernel_hemisphere(q));
    }
  }
  // and it does rotate: a point off the noise vector's plane moves
  glm::vec3 p(0.5f, 0.f, 0.5f);
  EXPECT_GT(glm::distance(reflect_about(p, glm::vec3(1, 0, 0)), p), 0.9f);
}

TEST(Bunnell, LimitsOfTheDiskTerms) {
  const glm::vec3 up(0, 1, 0), down(0, -1, 0), o(0);
  for (auto term : {bunnell_occlusion, form_factor_occlusion}) {
    // far disk -> 0 (as A / d^2)
    EXPECT_LT(term(o, up, glm::vec3(0, 1000, 0), down, 1.f), 1e-6f);
    // behind the receiver (below its tangent plane) -> 0
    EXPECT_EQ(term(o, up, glm::vec3(0, -1, 0), up, 1.f), 0.f);
    // edge-on (in the receiver's own plane) -> 0: a flat floor does not occlude itself
    EXPECT_EQ(term(o, up, glm::vec3(1, 0, 0), up, 1.f), 0.f);
    // facing disks, close and large -> fully occluded
    EXPECT_GT(term(o, up, glm::vec3(0, 1e-4f, 0), down, 1.f), 0.999f);  // Bunnell: 1 - d sqrt(pi / A) = 0.99982
  }
  // on the axis both are exact for their measure: a disk of radius a at distance d
  const float a = 0.5f, d = 1.f, A = kPi * a * a;
  const glm::vec3 e(0, d, 0);
  EXPECT_NEAR(bunnell_occlusion(o, up, e, down, A), 1.f - d / std::sqrt(d * d + a * a), 1e-6f);  // solid angle / 2 pi
  EXPECT_NEAR(form_factor_occlusion(o, up, e, down, A), a * a / (a * a + d * d), 1e-6f);        // sin^2 of the half-angle
  // a small disk (A / (pi d^2) = x = 0.003): Bunnell's is half the form factor (solid angle over
  // 2 pi against cosine over pi), to first order: the ratio is 0.5 (1 + x / 4) = 0.5004
  EXPECT_NEAR(bunnell_occlusion(o, up, e, down, 0.01f) / form_factor_occlusion(o, up, e, down, 0.01f), 0.5f, 1e-3f);
}

TEST(Bilateral, WeightsFollowTheThresholds) {
  const glm::vec3 n(0, 0, 1);
  EXPECT_EQ(bilateral_weight(10.f, 10.4f, n, n, 0.05f, 0.8f), 1.f);   // 4 % deeper: same surface
  EXPECT_EQ(bilateral_weight(10.f, 10.6f, n, n, 0.05f, 0.8f), 0.f);   // 6 %: another surface
  EXPECT_EQ(bilateral_weight(10.f, 10.f, n, glm::normalize(glm::vec3(1, 0, 1)), 0.05f, 0.8f), 0.f);  // 45 degrees
  EXPECT_EQ(bilateral_weight(10.f, 10.f, n, glm::normalize(glm::vec3(0.5f, 0, 1)), 0.05f, 0.8f), 1.f);  // 27 degrees
  EXPECT_EQ(bilateral_weight(10.f, 0.f, n, n, 0.05f, 0.8f), 0.f);     // the sky never counts
}

TEST(Truth, CosineDirectionsHaveTheCosineDensity) {
  // E[n . w] under the density cos / pi is 2/3; and every direction is above the surface
  Pcg32 rng(9, 1);
  const glm::vec3 n = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
  double sum = 0;
  const int count = 200000;
  for (int i = 0; i < count; ++i) {
    float u1 = rng.uniform(), u2 = rng.uniform();
    glm::vec3 w = cosine_direction(n, u1, u2);
    ASSERT_GE(glm::dot(w, n), -1e-6f);
    sum += glm::dot(w, n);
  }
  // standard deviation of n.w is sqrt(1/2 - 4/9) = 0.236: the mean's is 0.236 / sqrt(2e5) = 5e-4
  EXPECT_NEAR(sum / count, 2.0 / 3.0, 3e-3);
}

TEST(Spiral, EqualAreaRingsInsideTheUnitDisk) {
  for (int n : {8, 32}) {
    int inner = 0;
    for (int i = 0; i < n; ++i) {
      glm::vec2 p = spiral_point(i, n);
      EXPECT_LE(glm::length(p), 1.f);
      inner += glm::length(p) < std::sqrt(0.5f);
    }
    EXPECT_EQ(inner, n / 2);  // half the samples in the inner half of the area
  }
}

namespace lp::ch07 {
namespace {

// Simpson's rule with 2000 intervals: its error for these smooth integrands over at most pi is
// below 1e-12, far under the float evaluation's.
double simpson(double a, double b, const std::function<double(double)>& f) {
  const int n = 2000;
  const double h = (b - a) / n;
  double sum = f(a) + f(b);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4 : 2) * f(a + i * h);
  return sum * h / 3;
}

TEST(GtaoArc, IsTheCosineWeightedIntegralFromTheViewVectorToTheHorizon) {
  // gtao_arc(h, n) against the integral of |sin t| cos(t - n) between 0 and h, for normals
  // within the hemisphere about the view vector and horizons within pi/2 of the normal. The
  // float evaluation's terms are at most (1 + pi + 1) / 4 in size, each within 2 ulp (sin and
  // cos of std::, correctly rounded nearly), so 8 ulp of 2: 1e-6.
  Pcg32 rng(7, 1);
  for (int k = 0; k < 2000; ++k) {
    const double n = (rng.uniform() - 0.5) * 3.14159265358979;
    const double h = n + (rng.uniform() - 0.5) * 3.14159265358979;
    const double truth = simpson(0, h, [n](double t) { return std::abs(std::sin(t)) * std::cos(t - n); }) * (h >= 0 ? 1 : -1);
    ASSERT_NEAR(gtao_arc(float(h), float(n), float(std::cos(n))), truth, 1e-6) << "h " << h << " n " << n;
  }
}

TEST(GtaoArc, BothSidesAtTheTangentPlaneGiveTheOpenSlice) {
  // h = n - pi/2 and n + pi/2 (nothing above the tangent plane): cos n + n sin n, the open
  // slice ssao.comp divides by. Within 1e-6 as above.
  const float half_pi = 1.5707963f;
  for (float n = -1.5f; n <= 1.5f; n += 0.125f) {
    const float open = gtao_arc(n - half_pi, n, std::cos(n)) + gtao_arc(n + half_pi, n, std::cos(n));
    EXPECT_NEAR(open, std::cos(n) + n * std::sin(n), 1e-6) << n;
  }
}

TEST(GtaoHorizon, ElevationWhereSeenAndTheSlicesLowestWhereNot) {
  const glm::vec3 p(0, 0, -2), view(0, 0, 1), normal(0, 1, 0);
  const float low = -0.25f, falloff_mul = -1.f / 0.05f, falloff_add = 0.95f / 0.05f + 1.f;  // R = 1: full to 0.95
  // 0.5 up and 0.5 toward the camera: elevation cos 45 degrees = 0.7071, full weight
  EXPECT_NEAR(gtao_horizon(p, p + glm::vec3(0, 0.5f, 0.5f), normal, view, low, falloff_mul, falloff_add, 0.01f), 0.70710678f, 1e-6f);
  // beyond R: the falloff's weight 0, the lowest value
  EXPECT_EQ(gtao_horizon(p, p + glm::vec3(0, 1.f, 1.f), normal, view, low, falloff_mul, falloff_add, 0.01f), low);
  // below the bias height: the surface itself, not an occluder
  EXPECT_EQ(gtao_horizon(p, p + glm::vec3(0, 0.005f, 0.5f), normal, view, low, falloff_mul, falloff_add, 0.01f), low);
  // halfway through the falloff (0.975 R): half the way from low to the elevation
  const glm::vec3 d = glm::normalize(glm::vec3(0, 1, 1)) * 0.975f;
  EXPECT_NEAR(gtao_horizon(p, p + d, normal, view, low, falloff_mul, falloff_add, 0.01f), low + 0.5f * (0.70710678f - low), 1e-5f);
  // the receiver itself: the lowest value
  EXPECT_EQ(gtao_horizon(p, p, normal, view, low, falloff_mul, falloff_add, 0.01f), low);
}

TEST(RangeWeight, FullWithinTheRadiusAndFadingBeyond) {
  EXPECT_EQ(range_weight(1.f, 0.f), 1.f);
  EXPECT_EQ(range_weight(1.f, -0.9f), 1.f);
  EXPECT_EQ(range_weight(1.f, 1.f), 1.f);
  EXPECT_NEAR(range_weight(1.f, 2.f), 0.5f, 1e-7f);     // smoothstep(0.5)
  EXPECT_NEAR(range_weight(1.f, -4.f), 0.15625f, 1e-7f);  // 0.25^2 (3 - 0.5)
  EXPECT_LT(range_weight(1.f, 100.f), 1e-3f);
}

}  // namespace
}  // namespace lp::ch07
