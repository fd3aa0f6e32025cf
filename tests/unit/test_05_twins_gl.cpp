// Chapter 05's GLSL functions against their C++ twins (hdr_math.h), on the GPU (glsl_twin.h):
// hdr_math.glsl's luminance, sanitize, log_luminance, the four curves, adapt and bright_pass.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "chapters/05_hdr/hdr_math.h"
#include "tests/unit/glsl_twin.h"

namespace lp::ch05 {
namespace {

using test::TwinCase;
using test::ulps;
constexpr float kInf = std::numeric_limits<float>::infinity();
const std::vector<std::string> kHdr = {"05_hdr/shaders/hdr_math.glsl"};
// GLSL may flush a denormal to zero (a value below the smallest normal float, 2^-126).
constexpr double kDenormal = 0x1p-126;

std::string describe_ab(const std::vector<TwinCase>& cases, std::size_t i) {
  return "a " + test::str(cases[i].a) + " b " + test::str(cases[i].b);
}

// Random radiances: each channel log-uniform over 12 decades below 65504, some exactly 0.
glm::vec3 radiance(test::TwinRandom& r) {
  auto channel = [&] { return r.uniform(0, 1) < 0.05f ? 0.f : r.log_uniform(1e-7f, kHalfMax); };
  return {channel(), channel(), channel()};
}

TEST(GlslTwins, SanitizeAndLuminanceMatchTheirCppTwins) {
  // sanitize: NaN in any channel, +-Inf, 65504 and just above, negative zero and values,
  // denormals, and random values over the float range of both signs. It only compares and
  // clamps: exact, but for a denormal GLSL may flush to 0. luminance of sanitized colours:
  // a 3-term dot of non-negative terms, 2 ulp on each side (4 relative).
  test::TwinRandom r(5);
  const float nan = std::nanf("");
  std::vector<TwinCase> cases;
  for (float v : {0.f, -0.f, 1.f, -1.f, kHalfMax, std::nextafter(kHalfMax, kInf), kInf, -kInf, 1e-40f, 1e38f})
    cases.push_back({glm::vec4(v, 0.5f, v, 0)});
  for (int k = 0; k < 3; ++k) {
    glm::vec4 c(1, 2, 3, 0);
    c[k] = nan;
    cases.push_back({c});
  }
  while (cases.size() < 10000 + 13) {
    auto v = [&] { return (r.uniform(0, 1) < 0.5f ? -1.f : 1.f) * r.log_uniform(1e-30f, 1e30f); };
    cases.push_back({glm::vec4(v(), v(), v(), 0)});
  }
  const std::string helper = "vec4 twin_sanitize(vec4 a) { bool ok; vec3 c = sanitize(a.xyz, ok); return vec4(c, ok ? 1.0 : 0.0); }";
  const auto gpu = test::run_glsl_twin({kHdr, "twin_sanitize(a)", {}, helper}, cases);
  std::vector<glm::vec4> cpu;
  for (const auto& c : cases) {
    Sanitized s = sanitize(glm::vec3(c.a));
    cpu.push_back(glm::vec4(s.rgb, s.valid ? 1.f : 0.f));
  }
  auto describe = [&](std::size_t i) { return describe_ab(cases, i); };
  EXPECT_TRUE(test::twins_agree(gpu, cpu, 4, {kDenormal, 0}, describe));

  std::vector<TwinCase> colours;
  for (const auto& c : cpu) colours.push_back({glm::vec4(glm::vec3(c), 0)});
  const auto gpu_y = test::run_glsl_twin({kHdr, "luminance(a.rgb)"}, colours);
  std::vector<glm::vec4> cpu_y;
  for (const auto& c : colours) cpu_y.push_back(glm::vec4(luminance(glm::vec3(c.a))));
  EXPECT_TRUE(test::twins_agree(gpu_y, cpu_y, 1, {kDenormal, ulps(4)}, [&](std::size_t i) { return describe_ab(colours, i); }));
}

TEST(GlslTwins, LogLuminanceMatchesItsCppTwin) {
  // log(delta + L) over sanitized radiances and deltas from 1e-6 to 1, plus black. The
  // argument: luminance (2 ulp) plus delta (0.5), on each side: 5 ulp relative, which log
  // turns into 5 ulp absolutely; GLSL's log itself may be off by 2^-21 absolutely on
  // [0.5, 2] and 3 ulp elsewhere, the C++ one by 1 ulp.
  test::TwinRandom r(6);
  std::vector<TwinCase> cases;
  for (float delta : {1e-6f, 1e-4f, 1.f}) cases.push_back({glm::vec4(0, 0, 0, delta)});
  cases.push_back({glm::vec4(kHalfMax, kHalfMax, kHalfMax, 1e-4f)});
  while (cases.size() < 10000 + 4) cases.push_back({glm::vec4(radiance(r), r.log_uniform(1e-6f, 1))});
  const auto gpu = test::run_glsl_twin({kHdr, "log_luminance(a.rgb, a.w)"}, cases);
  std::vector<glm::vec4> cpu;
  for (const auto& c : cases) cpu.push_back(glm::vec4(log_luminance(glm::vec3(c.a), c.a.w)));
  EXPECT_TRUE(test::twins_agree(gpu, cpu, 1, {0x1p-21 + ulps(5), ulps(4)}, [&](std::size_t i) { return describe_ab(cases, i); }));
}

TEST(GlslTwins, ToneCurvesMatchTheirCppTwins) {
  // The four curves over exposed values log-uniform from 1e-6 to 65504 x 1e4 (the largest
  // radiance at a large exposure) and whites from 1 to 20, plus 0, 1 and the ends. Tolerance,
  // relative, from the operations on each side (GLSL's division 2.5 ulp, C++'s 0.5): clamp
  // exact; Reinhard 3 + 1; extended Reinhard (x / w^2, 1 +, x *, / (1 + x)) 8 + 4; ACES (two
  // 3-operation polynomials of positive terms and a division) 6 + 4. Inputs of 1e19 and more
  // (x^2 overflows) are left out: there ACES is inf / inf, and GLSL's clamp of a NaN is
  // undefined; no exposed radiance reaches it.
  test::TwinRandom r(7);
  std::vector<TwinCase> cases;
  for (float x : {0.f, 1e-6f, 0.5f, 1.f, 7.2f, kHalfMax, kHalfMax * 1e4f})
    for (float white : {1.f, 4.f, 20.f}) cases.push_back({glm::vec4(x, white, 0, 0)});
  while (cases.size() < 10000 + 21) cases.push_back({glm::vec4(r.log_uniform(1e-6f, kHalfMax * 1e4f), r.uniform(1, 20), 0, 0)});
  const auto gpu = test::run_glsl_twin(
      {kHdr, "tonemap(OP_CLAMP, a.xxx, a.y).x, tonemap(OP_REINHARD, a.xxx, a.y).x, tonemap(OP_REINHARD_EXTENDED, a.xxx, a.y).x, "
             "tonemap(OP_ACES, a.xxx, a.y).x"},
      cases);
  std::vector<glm::vec4> cpu;
  for (const auto& c : cases) {
    const float x = c.a.x, w = c.a.y;
    cpu.push_back({tonemap(Operator::Clamp, x, w), tonemap(Operator::Reinhard, x, w),
                   tonemap(Operator::ReinhardExtended, x, w), tonemap(Operator::Aces, x, w)});
  }
  const double tolerance[4] = {0, ulps(4), ulps(12), ulps(10)};
  for (int op = 0; op < 4; ++op) {
    std::vector<glm::vec4> g, c;
    for (std::size_t i = 0; i < cases.size(); ++i) {
      g.push_back(glm::vec4(gpu[i][op]));
      c.push_back(glm::vec4(cpu[i][op]));
    }
    EXPECT_TRUE(test::twins_agree(g, c, 1, {kDenormal, tolerance[op]}, [&](std::size_t i) { return describe_ab(cases, i); }))
        << kOperatorNames[std::size_t(op)];
  }
}

TEST(GlslTwins, AdaptMatchesItsCppTwin) {
  // adapted + (target - adapted)(1 - exp(-dt / tau)) over luminances log-uniform from 1e-4
  // to 1e4, frame times to 1 s and time constants to 5 s, plus tau = 0 (at once), dt = 0 and
  // dt much longer than tau. k = 1 - exp(-x), x = dt / tau: x is off by 2.5 ulp (GLSL's
  // division), exp by 3 + 2x ulp (GLSL's allowance), which leaves e^-x (5.5 + 2x) ulp
  // absolutely in k, plus 1 ulp of 1 for the subtraction; the C++ side has 2.5 + 1. The result
  // moves by |target - adapted| times that, plus 2 ulp of the larger of adapted and the result.
  test::TwinRandom r(8);
  std::vector<TwinCase> cases;
  for (float tau : {0.f, 0.1f, 1.f})
    for (float dt : {0.f, 1e-3f, 1.f, 100.f}) cases.push_back({glm::vec4(0.2f, 50.f, dt, tau)});
  while (cases.size() < 10000 + 12)
    cases.push_back({glm::vec4(r.log_uniform(1e-4f, 1e4f), r.log_uniform(1e-4f, 1e4f), r.uniform(0, 1), r.uniform(0, 5))});
  const auto gpu = test::run_glsl_twin({kHdr, "adapt(a.x, a.y, a.z, a.w)"}, cases);
  std::vector<glm::vec4> cpu;
  for (const auto& c : cases) cpu.push_back(glm::vec4(adapt(c.a.x, c.a.y, c.a.z, c.a.w)));
  EXPECT_TRUE(test::twins_agree(
      gpu, cpu, 1,
      [&](std::size_t i) {
        const auto& a = cases[i].a;
        const double x = a.w > 0 ? double(a.z) / a.w : 0;
        const double k_error = std::exp(-x) * ulps(5.5 + 2 * x + 3.5) + ulps(2);
        return test::TwinTolerance{std::abs(double(a.y) - a.x) * k_error, ulps(2)};
      },
      [&](std::size_t i) { return "adapted, target, dt, tau = " + test::str(cases[i].a); }));
}

TEST(GlslTwins, BrightPassMatchesItsCppTwin) {
  // x (min(y - threshold, limit) / y) over random radiances, thresholds and limits, plus a
  // pixel at the threshold, black and 65504. y is 2 ulp off on each side, which y - threshold
  // carries as 2 ulp of y absolutely: x's channel times 4 ulp on both; the quotient and the
  // product add 3.5 ulp (GLSL) and 1 (C++) relative. At the threshold the two may take
  // different branches: 0 against an excess within that absolute tolerance.
  test::TwinRandom r(9);
  std::vector<TwinCase> cases;
  cases.push_back({glm::vec4(1, 1, 1, 0), glm::vec4(1, 4, 0, 0)});  // y = threshold
  cases.push_back({glm::vec4(0), glm::vec4(0, 4, 0, 0)});
  cases.push_back({glm::vec4(kHalfMax, kHalfMax, kHalfMax, 0), glm::vec4(1, 4, 0, 0)});
  while (cases.size() < 10000 + 3)
    cases.push_back({glm::vec4(radiance(r) * 1e-3f, 0), glm::vec4(r.uniform(0, 4), r.log_uniform(0.1f, 100), 0, 0)});
  const auto gpu = test::run_glsl_twin({kHdr, "bright_pass(a.rgb, b.x, b.y), 0.0"}, cases);
  std::vector<glm::vec4> cpu;
  for (const auto& c : cases) cpu.push_back(glm::vec4(bright_pass(glm::vec3(c.a), c.b.x, c.b.y), 0));
  EXPECT_TRUE(test::twins_agree(
      gpu, cpu, 3,
      [&](std::size_t i) {
        const auto& x = cases[i].a;
        return test::TwinTolerance{std::max({x.r, x.g, x.b}) * ulps(8) + kDenormal, ulps(5)};
      },
      [&](std::size_t i) { return describe_ab(cases, i); }));
}

}  // namespace
}  // namespace lp::ch05
