// Chapter 04's maths (neon.h): closest points, the ground truth and every approximation held
// to it, and the hard cases. Bounds are derived where a formula gives them, otherwise the
// measured value with a stated margin (the numbers the book quotes come from these tests).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "chapters/01_forward/blinn_phong.h"
#include "chapters/04_neon/neon.h"
#include "common/error.h"
#include "common/image.h"
#include "test_04_configs.h"
#include "tests/unit/book_data.h"

using namespace lp;
using namespace lp::ch04;
using namespace lp::ch04::testing;

namespace {

bool finite(const Terms& t) { return std::isfinite(t.diffuse) && std::isfinite(t.specular); }

// Distance from a point to the ray origin + t dir, t >= 0.
float point_ray_distance(const glm::vec3& p, const glm::vec3& o, const glm::vec3& dir) {
  float t = std::max(glm::dot(p - o, dir), 0.f);
  return glm::length(p - (o + t * dir));
}

// The segment-ray distance by brute force: dense sampling of the segment, then refinement.
float brute_force_distance(const glm::vec3& a, const glm::vec3& b, const glm::vec3& o, const glm::vec3& dir) {
  float best = std::numeric_limits<float>::max(), best_s = 0;
  for (int i = 0; i <= 2000; ++i) {
    float s = static_cast<float>(i) / 2000.f, d = point_ray_distance(glm::mix(a, b, s), o, dir);
    if (d < best) best = d, best_s = s;
  }
  for (int i = -200; i <= 200; ++i) {  // around the best sample, 100x finer
    float s = std::clamp(best_s + static_cast<float>(i) * 5e-6f, 0.f, 1.f);
    best = std::min(best, point_ray_distance(glm::mix(a, b, s), o, dir));
  }
  return best;
}

const std::vector<Config>& configs() {
  static const std::vector<Config> c = test_configs(500);
  return c;
}

struct Stats {
  float mean = 0, median = 0, p99 = 0, max = 0;
};
Stats stats(std::vector<float> v) {
  std::sort(v.begin(), v.end());
  Stats s;
  for (float x : v) s.mean += x / static_cast<float>(v.size());
  s.median = v[v.size() / 2];
  s.p99 = v[std::min(v.size() - 1, static_cast<size_t>(std::ceil(0.99 * static_cast<double>(v.size()))) - 1)];
  s.max = v.back();
  return s;
}

// Errors of one method over the configurations, per term.
std::pair<Stats, Stats> method_errors(const std::function<Terms(const NeonSurface&)>& method, bool print_name = true,
                                      const char* name = "") {
  std::vector<float> d, s;
  for (const auto& c : configs()) {
    Terms t = method(c.surface);
    EXPECT_TRUE(finite(t)) << name;
    d.push_back(diffuse_error(t.diffuse, c));
    s.push_back(specular_error(t.specular, c));
  }
  Stats sd = stats(d), ss = stats(s);
  if (print_name)
    lp::test::book_row_cpu("04_neon_math", {{"method", name}},
                           {{"diffuse_mean", sd.mean}, {"diffuse_median", sd.median}, {"diffuse_p99", sd.p99}, {"diffuse_max", sd.max},
                            {"specular_mean", ss.mean}, {"specular_median", ss.median}, {"specular_p99", ss.p99},
                            {"specular_max", ss.max}, {"configurations", double(configs().size())}});
  if (print_name)
    std::printf("  %-22s diffuse: mean %9.6f median %9.6f p99 %9.6f max %9.4f | specular: mean %9.6f median %9.6f p99 %9.6f max %9.4f\n",
                name, sd.mean, sd.median, sd.p99, sd.max, ss.mean, ss.median, ss.p99, ss.max);
  return {sd, ss};
}

}  // namespace

// --- Closest points --------------------------------------------------------------------------

TEST(NeonGeometry, ClosestOnSegmentClampsAndHandlesZeroLength) {
  glm::vec3 a(0, 0, 0), b(2, 0, 0);
  EXPECT_FLOAT_EQ(closest_on_segment({1, 5, 0}, a, b), 0.5f);
  EXPECT_FLOAT_EQ(closest_on_segment({-3, 1, 0}, a, b), 0.f);
  EXPECT_FLOAT_EQ(closest_on_segment({9, 1, 0}, a, b), 1.f);
  EXPECT_FLOAT_EQ(closest_on_segment({9, 1, 0}, a, a), 0.f);  // zero length: the only point
}

TEST(NeonGeometry, SegmentRayMatchesBruteForce) {
  Random rng(11);
  for (int i = 0; i < 300; ++i) {
    glm::vec3 a = rng.direction() * 2.f, b = a + rng.direction() * (0.1f + 3.f * rng.uniform());
    glm::vec3 o = rng.direction() * 3.f, dir = rng.direction();
    SegmentRayClosest c = closest_segment_ray(a, b, o, dir);
    ASSERT_TRUE(std::isfinite(c.distance));
    EXPECT_GE(c.s, 0.f);
    EXPECT_LE(c.s, 1.f);
    EXPECT_GE(c.t, 0.f);
    EXPECT_NEAR(glm::length(c.on_segment - c.on_ray), c.distance, 1e-5f);
    // A true closest pair: no point of the segment is nearer the ray (float rounding: 1e-4).
    EXPECT_NEAR(c.distance, brute_force_distance(a, b, o, dir), 1e-4f) << "case " << i;
  }
}

TEST(NeonGeometry, SegmentRayThroughParallelIsContinuousAndNeverNaN) {
  // The ray turns through the segment's direction (and its opposite) in steps down to 1e-9 rad;
  // the distance must stay a true minimum and change no faster than the geometry allows:
  // turning the ray by da moves its points at distance <= r by <= r da.
  glm::vec3 a(-1, 0, 0), b(1, 0, 0), o(-2.5f, 0.3f, 0.2f);
  for (float sign : {1.f, -1.f}) {
    std::vector<float> angles;
    for (float e = -2.f; e >= -9.f; e -= 0.25f) angles.push_back(std::pow(10.f, e));
    for (float e = -9.f; e <= -2.f; e += 0.25f) angles.push_back(-std::pow(10.f, e));
    angles.push_back(0.f);
    std::sort(angles.begin(), angles.end());
    float previous = -1, previous_angle = 0;
    for (float angle : angles) {
      glm::vec3 dir = sign * glm::vec3(std::cos(angle), std::sin(angle), 0);
      SegmentRayClosest c = closest_segment_ray(a, b, o, dir);
      ASSERT_TRUE(std::isfinite(c.distance) && std::isfinite(c.s) && std::isfinite(c.t)) << angle;
      EXPECT_NEAR(c.distance, brute_force_distance(a, b, o, dir), 2e-4f) << "angle " << angle;
      if (previous >= 0) {
        EXPECT_LE(std::abs(c.distance - previous), 6.f * std::abs(angle - previous_angle) + 2e-4f);
      }
      previous = c.distance;
      previous_angle = angle;
    }
  }
  // Exactly parallel, ray starting before the segment: every point is at the same distance;
  // we pick the one nearest the origin.
  SegmentRayClosest c = closest_segment_ray(a, b, o, {1, 0, 0});
  EXPECT_TRUE(c.parallel);
  EXPECT_NEAR(c.distance, std::sqrt(0.3f * 0.3f + 0.2f * 0.2f), 1e-6f);
  EXPECT_FLOAT_EQ(c.s, 0.f);
}

TEST(NeonGeometry, SegmentRayDegenerateCases) {
  glm::vec3 a(-1, 0, 0), b(1, 0, 0);
  // A zero-length segment: the distance from a point to the ray.
  SegmentRayClosest p = closest_segment_ray(a, a, {0, 1, 0}, glm::normalize(glm::vec3(-1, -1, 0)));
  EXPECT_NEAR(p.distance, 0.f, 1e-6f);
  EXPECT_NEAR(p.t, std::sqrt(2.f), 1e-5f);
  SegmentRayClosest q = closest_segment_ray(a, a, {0, 1, 0}, {0, 1, 0});  // pointing away: its origin
  EXPECT_FLOAT_EQ(q.t, 0.f);
  EXPECT_NEAR(q.distance, std::sqrt(2.f), 1e-6f);
  // A ray starting on the segment, in any direction: distance 0 at the origin.
  for (glm::vec3 dir : {glm::vec3(0, 1, 0), glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0), glm::normalize(glm::vec3(1, 1, 1))}) {
    SegmentRayClosest c = closest_segment_ray(a, b, {0.25f, 0, 0}, dir);
    EXPECT_NEAR(c.distance, 0.f, 1e-6f);
    EXPECT_NEAR(glm::length(c.on_segment - glm::vec3(0.25f, 0, 0)), 0.f, 1e-6f);
  }
  // A ray pointing away from the segment: the pair is the segment's point nearest the origin.
  SegmentRayClosest away = closest_segment_ray(a, b, {3, 1, 0}, {1, 0, 0});
  EXPECT_FLOAT_EQ(away.t, 0.f);
  EXPECT_FLOAT_EQ(away.s, 1.f);
}

// --- The ground truth --------------------------------------------------------------------------

TEST(NeonGroundTruth, MidpointRuleConvergesAsOneOverNSquared) {
  // The midpoint rule's error is -(h^2 / 24) times the integral of f'' plus O(h^4): halving h
  // divides it by 4. Over the horizon-clipped part the integrand is smooth, so this holds
  // with clipping too (the second surface sees only part of the tube).
  NeonLight tube = test_tube();
  for (NeonSurface s : {NeonSurface{{0.3f, 0.5f, 0.2f}, glm::normalize(glm::vec3(0.2f, -1, -0.3f)), glm::normalize(glm::vec3(0.5f, -1, 0.4f)), 16},
                    NeonSurface{{0.3f, 0.4f, 0.f}, glm::normalize(glm::vec3(-0.8f, -0.6f, 0.f)), glm::normalize(glm::vec3(0.1f, -1, 0.3f)), 16}}) {
    Terms reference = ground_truth_terms(s, tube, 16384);
    double previous_d = 0, previous_s = 0;
    for (int n = 16; n <= 128; n *= 2) {
      Terms t = ground_truth_terms(s, tube, n);
      double ed = std::abs(t.diffuse - reference.diffuse), es = std::abs(t.specular - reference.specular);
      if (previous_d > 0) {
        EXPECT_NEAR(previous_d / ed, 4.0, 0.5) << "diffuse, " << n << " samples";
        EXPECT_NEAR(previous_s / es, 4.0, 0.5) << "specular, " << n << " samples";
      }
      previous_d = ed;
      previous_s = es;
    }
    // And with 256 samples (the program's ground-truth mode) it is within 0.05 % here.
    Terms t256 = ground_truth_terms(s, tube, 256);
    EXPECT_NEAR(t256.diffuse / reference.diffuse, 1.0, 5e-4);
    EXPECT_NEAR(t256.specular / reference.specular, 1.0, 5e-4);
  }
}

TEST(NeonGroundTruth, LimitsOfALineLight) {
  // Far away the tube is a point light of the whole intensity: E = I cos / d^2 (to O(L^2/d^2)).
  NeonLight tube = test_tube();
  NeonSurface far{{0, -100, 0}, {0, 1, 0}, {0, 1, 0}, 8};
  EXPECT_NEAR(ground_truth_terms(far, tube, 256).diffuse * 1e4f, 1.f, 1e-4f);
  // Close to a long tube it is an infinite line: E = (I / L) 2 / d, facing it.
  NeonLight line = tube;
  line.start = {-500, 0, 0};
  line.end = {500, 0, 0};
  NeonSurface close{{0, -0.5f, 0}, {0, 1, 0}, {0, 1, 0}, 8};
  EXPECT_NEAR(analytic_diffuse_terms(close, line).diffuse, 2.f / 1000.f / 0.5f, 1e-6f);
  // In front of the middle of a finite tube: E = I / (d sqrt(d^2 + L^2 / 4)).
  NeonSurface front{{0, -0.7f, 0}, {0, 1, 0}, {0, 1, 0}, 8};
  EXPECT_NEAR(ground_truth_terms(front, tube, 4096).diffuse, 1.f / (0.7f * std::sqrt(0.49f + 1.f)), 1e-5f);
}

TEST(NeonGroundTruth, OnlyThePartAboveTheHorizonLights) {
  // A surface whose tangent plane cuts the tube at x = 0.2: the truth equals that of the
  // visible piece alone (0.8 of the 2 m, so 0.4 of the intensity), the rest gives nothing.
  NeonLight tube = test_tube();
  glm::vec3 n = glm::normalize(glm::vec3(1, -1, 0));  // sees the tube where x > 0.2
  glm::vec3 offset(0.3f, 0.3f, 0.6f);
  NeonSurface s{glm::vec3(0.2f, 0, 0) + offset - glm::dot(offset, n) * n, n, n, 8};  // its plane holds (0.2, 0, 0)
  NeonLight piece = tube;
  piece.start = {0.2f, 0, 0};
  Terms whole = ground_truth_terms(s, tube, 8192), visible = ground_truth_terms(s, piece, 8192);
  EXPECT_GT(whole.diffuse, 0.f);
  EXPECT_NEAR(whole.diffuse / visible.diffuse, 0.4f, 1e-5f);
  EXPECT_NEAR(whole.specular / visible.specular, 0.4f, 1e-5f);
}

// --- The exact diffuse ---------------------------------------------------------------------

TEST(NeonAnalyticDiffuse, EqualsTheGroundTruth) {
  // Two independent evaluations of the same integral: the closed form and 8192 midpoint
  // samples (whose own error at 3 cm is (h / d)^2 / 24 ~ 3e-5 with h = 2 m / 8192).
  float worst = 0;
  for (const auto& c : configs()) {
    Terms a = analytic_diffuse_terms(c.surface, test_tube());
    worst = std::max(worst, diffuse_error(a.diffuse, c));
    EXPECT_EQ(a.specular, 0.f);
  }
  EXPECT_LT(worst, 1e-3f);
}

TEST(NeonAnalyticDiffuse, ContinuousAsTheTubeSinksBelowTheHorizon) {
  // The surface turns until its tangent plane sweeps past the whole tube: the irradiance
  // falls smoothly to 0 (no jump where clipping starts or where the tube disappears).
  NeonLight tube = test_tube();
  float previous = -1;
  for (float angle = 0; angle <= 3.1416f; angle += 0.001f) {
    glm::vec3 n(std::sin(angle), -std::cos(angle), 0);  // from facing the tube (up) to facing away
    NeonSurface s{{0.4f, 0.3f, 0}, n, n, 8};
    float e = analytic_diffuse_terms(s, tube).diffuse;
    ASSERT_TRUE(std::isfinite(e));
    ASSERT_GE(e, 0.f);
    if (previous >= 0) {
      EXPECT_LT(std::abs(e - previous), 0.02f) << angle;  // |dE/dangle| <= E_max ~ 8
    }
    previous = e;
  }
  EXPECT_EQ(previous, 0.f);
}

// --- The approximations against the truth --------------------------------------------------

TEST(NeonMethods, ErrorsOnTheTestConfigurations) {
  // 3000 configurations (500 per exponent 1 .. 2048), 3 cm .. 2.5 m from a 2 m tube; the
  // truth is 8192 samples. Errors are relative: the diffuse to the truth, the specular to the
  // truth plus 2 % of the lobe's peak there (test_04_configs.h: a highlight of nearly nothing
  // must not divide by nothing). The bounds are the measured values (printed, llvmpipe's
  // machine, g++ 12 -O3) with a margin of 1.5x, both ways for the alternatives (a change in
  // them is noticed), or, for the exact ones, derived; the book quotes these lines.
  NeonLight tube = test_tube();
  std::printf("relative errors against the ground truth (8192 samples):\n");
  auto gt = method_errors([&](const NeonSurface& s) { return ground_truth_terms(s, tube, 256); }, true, "ground truth, 256");
  auto improved = method_errors([&](const NeonSurface& s) { return improved_terms(s, tube); }, true, "improved");
  auto analytic = method_errors([&](const NeonSurface& s) { return analytic_diffuse_terms(s, tube); }, true, "analytic diffuse");
  auto points8 = method_errors([&](const NeonSurface& s) { return points_terms(s, tube, 8); }, true, "8 points");
  auto points64 = method_errors([&](const NeonSurface& s) { return points_terms(s, tube, 64); }, true, "64 points");
  auto karis = method_errors([&](const NeonSurface& s) { return representative_point_terms(s, tube); }, true, "representative point");
  auto source = method_errors([&](const NeonSurface& s) { return source_terms(s, tube); }, true, "source (thesis)");
  (void)analytic;
  // 256 samples: the midpoint error ~ (h / d)^2 / 24 is 0.3 % at 3 cm (h = 7.8 mm), far less
  // elsewhere; a mirror-like lobe (n = 2048) that close is aliased, hence the specular's max.
  EXPECT_LT(gt.first.p99, 0.01f);
  EXPECT_LT(gt.first.max, 0.03f);
  EXPECT_LT(gt.second.p99, 0.01f);
  EXPECT_LT(gt.second.max, 0.9f);
  // Improved: diffuse exact (float rounding); specular measured 0.0029 % mean, 0.036 % p99,
  // 2.84 % max (one grazing view of a rough surface; the book quotes 04_neon_math.csv, which
  // book_row_cpu above holds equal to this run).
  EXPECT_LT(improved.first.max, 1e-3f);
  EXPECT_LT(improved.second.mean, 1.5f * 2.9e-5f);
  EXPECT_LT(improved.second.p99, 1.5f * 3.61e-4f);
  EXPECT_LT(improved.second.max, 1.5f * 0.0284f);
  // The others are far off, each for its known reason (see the hard-case tests below),
  // pinned within 1.5x of what was measured.
  auto pinned = [](float value, float measured) { return value > measured / 1.5f && value < measured * 1.5f; };
  EXPECT_TRUE(pinned(points8.first.median, 0.01474f)) << points8.first.median;
  EXPECT_TRUE(pinned(points64.first.median, 1.87e-4f)) << points64.first.median;
  EXPECT_TRUE(pinned(points8.second.p99, 0.958f)) << points8.second.p99;
  EXPECT_TRUE(pinned(karis.first.median, 0.8375f)) << karis.first.median;  // the "+2" in metres
  EXPECT_TRUE(pinned(karis.second.p99, 17.50f)) << karis.second.p99;
  EXPECT_TRUE(pinned(source.first.median, 0.8789f)) << source.first.median;
  EXPECT_TRUE(pinned(source.second.median, 0.5182f)) << source.second.median;
  EXPECT_LT(improved.second.p99, std::min({points64.second.p99, karis.second.p99, source.second.p99}));
}

TEST(NeonMethods, RepresentativePointWithoutPlusTwoIsTheExactDiffuse) {
  // Karis's closed form without its "+ 2", (N.l0/|l0| + N.l1/|l1|) / (|l0||l1| + l0.l1), is
  // (1/L) times the integral of N.l / r^2 along the tube: our exact diffuse, wherever the
  // whole tube is above the horizon. And the code's result differs from it by the "+ 2" alone.
  NeonLight tube = test_tube();
  int checked = 0;
  for (const auto& c : configs()) {
    const NeonSurface& s = c.surface;
    glm::vec3 l0 = tube.start - s.position, l1 = tube.end - s.position;
    float n0 = glm::dot(s.normal, l0), n1 = glm::dot(s.normal, l1);
    if (n0 <= 0 || n1 <= 0) continue;  // part of the tube below the horizon: they differ there
    if (line_frame(s.position, tube, s.normal).d < 2 * tube.radius) continue;  // ours clamps d to the glass
    ++checked;
    float denominator = glm::length(l0) * glm::length(l1) + glm::dot(l0, l1);
    float closed = (n0 / glm::length(l0) + n1 / glm::length(l1)) / denominator;
    EXPECT_NEAR(closed / analytic_diffuse_terms(s, tube).diffuse, 1.f, 1e-3f);
    EXPECT_NEAR(representative_point_terms(s, tube).diffuse * (denominator + 2.f) / denominator / closed, 1.f, 1e-4f);
  }
  EXPECT_GT(checked, 1000);
}

TEST(NeonMethods, RepresentativePointBiasFromPlusTwo) {
  // Karis's diffuse for a short tube facing the surface is I / (d^2 + 1): the "+2" added to
  // |L0||L1| + L0.L1 = 2 d^2 halves it at 1 m and takes 6 % at 4 m (in metres; it was
  // tuned for centimetres, where it is a 2 cm^2 softening).
  NeonLight tube = test_tube();
  tube.start = {-0.01f, 0, 0};
  tube.end = {0.01f, 0, 0};
  for (float d : {1.f, 4.f}) {
    NeonSurface s{{0, -d, 0}, {0, 1, 0}, {0, 1, 0}, 8};
    float ratio = representative_point_terms(s, tube).diffuse / ground_truth_terms(s, tube, 256).diffuse;
    EXPECT_NEAR(ratio, d * d / (d * d + 1.f), 1e-4f) << d;
  }
  // And it gives nothing where the tube crosses the surface's plane symmetrically, though
  // half of the tube lights it.
  NeonSurface across{{0, 0.5f, 0}, {1, 0, 0}, {1, 0, 0}, 8};
  EXPECT_NEAR(representative_point_terms(across, test_tube()).diffuse, 0.f, 1e-6f);
  EXPECT_GT(ground_truth_terms(across, test_tube(), 256).diffuse, 0.1f);
}

// --- Hard cases ------------------------------------------------------------------------------

TEST(NeonHardCases, ReflectionRayParallelToTheTube) {
  // A wall parallel to the tube, seen so that its reflection rays turn through the tube's
  // direction. The improved specular stays finite and continuous (steps of 1e-4 rad change
  // it by < 2 % of its largest value); the thesis's jumps: its closest point flips from one
  // end to the other where the rays become parallel (the artefact it reports).
  NeonLight tube = test_tube();
  glm::vec3 x(0, 0, -0.3f), n(0, 0, 1);  // the wall point, 30 cm behind the tube's middle
  auto sweep = [&](auto method) {
    std::vector<float> v;
    for (float a = -0.05f; a <= 0.05f; a += 1e-4f) {
      glm::vec3 r(std::cos(a), std::sin(a) * 0.3f, std::sin(a));  // reflection ray near +X
      r = glm::normalize(r);
      glm::vec3 eye = 2.f * glm::dot(n, r) * n - r;  // the view that reflects to r
      if (glm::dot(eye, n) <= 0) continue;
      Terms t = method(NeonSurface{x, n, eye, 128});
      EXPECT_TRUE(finite(t));
      v.push_back(t.specular);
    }
    return v;
  };
  auto jump = [](const std::vector<float>& v) {
    float top = *std::max_element(v.begin(), v.end()), worst = 0;
    for (size_t i = 1; i < v.size(); ++i) worst = std::max(worst, std::abs(v[i] - v[i - 1]));
    return worst / std::max(top, 1e-20f);
  };
  std::vector<float> improved = sweep([&](const NeonSurface& s) { return improved_terms(s, tube); });
  std::vector<float> truth = sweep([&](const NeonSurface& s) { return ground_truth_terms(s, tube, 2048); });
  std::vector<float> source = sweep([&](const NeonSurface& s) { return source_terms(s, tube); });
  ASSERT_FALSE(improved.empty());
  EXPECT_LT(jump(improved), 0.02f);
  EXPECT_LT(jump(truth), 0.02f);
  EXPECT_GT(jump(source), 0.1f);
}

TEST(NeonHardCases, SurfaceTouchingTheTube) {
  // A floor touching the glass (3 cm from the axis, the tube's radius): every method finite;
  // the exact diffuse and the improved specular agree with 16384 samples (h = 0.12 mm).
  NeonLight tube = test_tube();
  tube.radius = 0.03f;
  for (float d : {0.03f, 0.01f, 0.f}) {  // touching, then inside the glass (distance clamped)
    NeonSurface s{{0.3f, -d, 0}, {0, 1, 0}, glm::normalize(glm::vec3(0.5f, 1, 0.2f)), 64};
    Terms truth = ground_truth_terms(s, tube, 16384);
    for (Method m : {Method::GroundTruth, Method::Source, Method::Improved, Method::Points,
                     Method::RepresentativePoint, Method::AnalyticDiffuse}) {
      NeonResult r = neon_light(s, tube, m, 64, volume_radius(tube));
      EXPECT_TRUE(std::isfinite(r.diffuse.x) && std::isfinite(r.specular.x)) << kMethodNames[int(m)] << " at " << d;
      EXPECT_GE(r.diffuse.x, 0.f);
    }
    EXPECT_NEAR(analytic_diffuse_terms(s, tube).diffuse / truth.diffuse, 1.f, 1e-3f) << d;
    EXPECT_NEAR(improved_terms(s, tube).specular / truth.specular, 1.f, 1e-2f) << d;
  }
}

TEST(NeonHardCases, ZeroLengthTubeIsChapter01PointLight) {
  NeonLight tube = test_tube();
  tube.start = tube.end = {0.5f, 0.2f, 0};
  NeonSurface s{{0, -1, 0.3f}, glm::normalize(glm::vec3(0.2f, 1, 0)), glm::normalize(glm::vec3(0.5f, 1, -0.3f)), 32};
  glm::vec3 to = tube.start - s.position;
  ch01::Reflected point = ch01::blinn_phong(s.normal, s.to_eye, glm::normalize(to), glm::vec3(1.f / glm::dot(to, to)), 32);
  for (auto terms : {ground_truth_terms(s, tube, 64), improved_terms(s, tube), points_terms(s, tube, 8),
                     analytic_diffuse_terms(s, tube)}) {
    EXPECT_NEAR(terms.diffuse, point.diffuse.x, 1e-5f);
  }
  EXPECT_NEAR(improved_terms(s, tube).specular, point.specular.x, 1e-5f);
  EXPECT_NEAR(ground_truth_terms(s, tube, 64).specular, point.specular.x, 1e-5f);
  EXPECT_TRUE(finite(representative_point_terms(s, tube)));
  EXPECT_TRUE(finite(source_terms(s, tube)));
  // Continuous as the tube shrinks to nothing: 1 mm long, centred on the point, is within
  // 0.1 % of it (the lobe changes by ~(n/8) (1 mm / 1 m)^2 over it).
  NeonLight short_tube = tube;
  short_tube.start = tube.start - glm::vec3(5e-4f, 0, 0);
  short_tube.end = tube.start + glm::vec3(5e-4f, 0, 0);
  EXPECT_NEAR(improved_terms(s, short_tube).diffuse / point.diffuse.x, 1.f, 1e-3f);
  EXPECT_NEAR(improved_terms(s, short_tube).specular / point.specular.x, 1.f, 1e-3f);
}

TEST(NeonHardCases, EndCapsOffCutTheLightAtTheEnds) {
  NeonLight tube = test_tube();
  float radius = volume_radius(tube);
  NeonLight cylinder = tube;
  cylinder.caps = false;
  NeonSurface beside{{0.9f, -0.5f, 0}, {0, 1, 0}, {0, 1, 0}, 16}, beyond{{1.1f, -0.5f, 0}, {0, 1, 0}, {0, 1, 0}, 16};
  for (Method m : {Method::GroundTruth, Method::Improved, Method::Source}) {
    NeonResult in_cap = neon_light(beside, tube, m, 64, radius), in_cyl = neon_light(beside, cylinder, m, 64, radius);
    EXPECT_EQ(in_cap.diffuse, in_cyl.diffuse);  // inside, the same light
    EXPECT_GT(neon_light(beyond, tube, m, 64, radius).diffuse.x, 0.f);
    EXPECT_EQ(neon_light(beyond, cylinder, m, 64, radius).diffuse, glm::vec3(0));  // beyond an end: none
  }
}

// --- The extent, the volume and the barn doors -----------------------------------------------

TEST(NeonExtent, VolumeRadiusIsWhereTheBrightestIrradianceIsOneSrgbStepAtBlack) {
  NeonLight tube = test_tube();
  tube.intensity = 1.2f;
  tube.color = {1, 0.2f, 0.5f};
  // The cut (neon.h): one sRGB step at black, 1 / (255 x 12.92), for a white matte surface.
  const float steps_per_unit = 1.f / kNeonCut;
  float r = volume_radius(tube);
  EXPECT_NEAR(max_irradiance_at(tube, r) * steps_per_unit, 1.f, 1e-4f);
  // It bounds the truth for a surface facing the tube's middle, by at most pi/2.
  NeonSurface s{{0, -r, 0}, {0, 1, 0}, {0, 1, 0}, 8};
  float facing = analytic_diffuse_terms(s, tube).diffuse * 1.2f * steps_per_unit;
  EXPECT_LE(facing, 1.f);
  EXPECT_GE(facing, 2.f / std::numbers::pi_v<float>);
  // A point light's radius sqrt(256 I); a long tube's from (I / L) pi / r = 1/256.
  NeonLight point = tube;
  point.end = point.start;
  EXPECT_NEAR(volume_radius(point), std::sqrt(steps_per_unit * 1.2f), 1e-3f * std::sqrt(steps_per_unit * 1.2f));
  NeonLight line = tube;
  line.start = {-1000, 0, 0};
  line.end = {1000, 0, 0};
  EXPECT_NEAR(volume_radius(line), 1.2f / 2000.f * std::numbers::pi_v<float> / (kNeonCut + 4 * 1.2f / (2000.f * 2000.f)), 1e-3f);
  // The source's cut, 1/256 linear, is 12.7 sRGB steps at black: the doors keep it as their scale.
  EXPECT_NEAR(max_irradiance_at(tube, doors_radius(tube)) * 256.f, 1.f, 1e-4f);
  EXPECT_NEAR(255.f * linear_to_srgb(1.f / 256.f), 12.67f, 0.01f);
}

TEST(NeonExtent, TheCutLosesAtMostOneSrgbStepOnAWhiteMatteSurface) {
  // What the volume's cut leaves out is the uncut truth beyond the radius (the other methods
  // give 0 there). On a white matte surface (albedo 1, no specular) turned towards the tube,
  // with the eye anywhere, it is below kNeonCut: less than one output step at black, however
  // dark the pixel. Sampled just beyond the radius all round the tube (the caps included) for
  // the scenes' shortest and longest tubes. The source's 1/256 cut left up to 12.7 steps.
  constexpr float pi = std::numbers::pi_v<float>;
  for (float length : {1.2f, 3.f}) {
    NeonLight tube = test_tube();
    tube.start = {-length / 2, 0, 0};
    tube.end = {length / 2, 0, 0};
    const float r = volume_radius(tube), old = volume_radius(tube, 1.f / 256.f);
    float worst = 0, worst_old = 0;
    for (float a = 0; a < 2 * pi; a += pi / 12) {       // around the axis
      for (float b = -pi / 2; b <= pi / 2; b += pi / 12) {  // along it and over the caps
        for (float radius : {r, old}) {
          const glm::vec3 centre = b < 0 ? tube.start : tube.end;
          const glm::vec3 dir(std::sin(b), std::cos(b) * std::cos(a), std::cos(b) * std::sin(a));
          const glm::vec3 x = centre + radius * 1.0001f * dir;
          const glm::vec3 to_tube = glm::normalize(tube.start + closest_on_segment(x, tube.start, tube.end) * (tube.end - tube.start) - x);
          const NeonSurface s{x, to_tube, to_tube, 1};
          const float truth = neon_light(s, tube, Method::GroundTruth, 256, r).diffuse.x;
          EXPECT_EQ(neon_light(s, tube, Method::Improved, 0, radius).diffuse.x, 0.f) << "beyond the volume: cut";
          (radius == r ? worst : worst_old) = std::max(radius == r ? worst : worst_old, 255.f * linear_to_srgb(truth));
        }
      }
    }
    std::printf("  tube %.1f m: cut at %.1f m loses at most %.3f steps (the source's %.1f m: %.2f)\n", length, r, worst, old,
                worst_old);
    EXPECT_LE(worst, 1.f) << length;
    EXPECT_GT(worst, 0.5f) << length << ": the bound is close, not loose";
    EXPECT_GT(worst_old, 5.f) << length;
  }
}

TEST(NeonExtent, VolumeMaskIsTheCapsuleOrTheCylinder) {
  NeonLight tube = test_tube();
  EXPECT_EQ(volume_mask({0, 2.9f, 0}, tube, 3.f), 1.f);
  EXPECT_EQ(volume_mask({0, 3.1f, 0}, tube, 3.f), 0.f);
  EXPECT_EQ(volume_mask({3.5f, 0.5f, 0}, tube, 3.f), 1.f);  // in the cap
  tube.caps = false;
  EXPECT_EQ(volume_mask({1.01f, 0.5f, 0}, tube, 3.f), 0.f);
  EXPECT_EQ(volume_mask({0.99f, 0.5f, 0}, tube, 3.f), 1.f);
}

TEST(NeonBarnDoors, MaskFollowsTheDoorsAroundTheAxis) {
  NeonLight tube = test_tube();
  float radius = 4.f;
  EXPECT_EQ(barn_doors_mask({0, 1, 0}, tube, radius), 1.f);  // no doors
  tube.barn_doors = {0.2f, 2, 0.35f, 1};                      // two doors: along +Y and -Y
  auto at = [&](float angle, float dist) {  // angle around the axis from +Y (the first door)
    return barn_doors_mask({0.3f, dist * std::cos(angle), dist * std::sin(angle)}, tube, radius);
  };
  constexpr float pi = std::numbers::pi_v<float>;
  EXPECT_EQ(at(0, 1), 0.f);                       // behind a door: 2 * 0.35 - cos 0 < 0
  EXPECT_EQ(at(pi, 1), 0.f);                      // behind the other
  EXPECT_FLOAT_EQ(at(pi / 2, 1), 1.f);            // between them: 0.7 - cos(pi) = 1.7 -> 1
  EXPECT_FLOAT_EQ(at(0.3f, 1), at(0.3f + pi, 1)); // two doors: period pi
  EXPECT_EQ(at(0, 0.1f), 1.f);                    // nearer than the doors' distance
  float near = at(0.9f, 0.5f), far = at(0.9f, 3.f);
  EXPECT_GT(near, 0.f);
  EXPECT_LT(near, far);                           // the shadow's edge softens with distance
  for (float a = 0; a < 6.3f; a += 0.05f) {
    float m = at(a, 1.5f);
    EXPECT_GE(m, 0.f);
    EXPECT_LE(m, 1.f);
  }
}

TEST(NeonMethods, NamesRoundTrip) {
  for (size_t i = 0; i < kMethodNames.size(); ++i) EXPECT_EQ(static_cast<size_t>(method_from_name(kMethodNames[i])), i);
  EXPECT_THROW(method_from_name("sparkly"), Error);
}
