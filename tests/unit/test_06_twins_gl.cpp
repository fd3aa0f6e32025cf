// Chapter 06's GLSL against its C++ twins (glsl_twin.h): convolution shadow maps' basis and
// reconstruction (csm_math.glsl against csm_math.h), moment shadow maps' Hamburger reconstruction
// and the pre-filter's moments (msm_math.glsl against shadow_math.h), ESM's log-space pre-filter
// and VSM's and ESM's lookups (filtered_math.glsl), the lookups' geometry (lookup_math.glsl),
// and the cube map's face table (cube_math.h) against the lookup point_visibility() makes, a
// samplerCubeArray read with a direction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/06_shadows/csm_math.h"
#include "chapters/06_shadows/cube_math.h"
#include "chapters/06_shadows/shadow_math.h"
#include "chapters/06_shadows/spot_atlas.h"
#include "common/gl.h"
#include "tests/unit/glsl_twin.h"

namespace lp::ch06 {
namespace {

using test::TwinCase;
const std::vector<std::string> kCsm = {"06_shadows/shaders/csm_math.glsl"};
// GLSL 4.50 gives sin and cos no precision. We allow 2^-20 absolutely (as chapter 07's twins),
// here for arguments up to 15 pi (c_8 z, z in [0, 1]): a bound on the implementation (llvmpipe's
// and NVIDIA's range reduction keep it), not the specification's. The C++ sinf adds at most an
// ulp of 1 (2^-24).
constexpr double kTrig = 0x1p-20 + 0x1p-24;
// u: float's unit roundoff, 2^-24 = ulps(0.5).
constexpr double kU = 0x1p-24;

std::string describe4(const std::vector<TwinCase>& cases, std::size_t i) {
  return test::str(cases[i].a) + " " + test::str(cases[i].b) + " " + test::str(cases[i].c) + " " + test::str(cases[i].d);
}

// The filtered basis of a texel's footprint holding two depths, z0 with weight w and z1 with
// 1 - w (what the pre-filter makes at a shadow's edge), reconstructed at the receiver's depth d
// with 1..8 terms: a = (z0, z1, w, _), b = (d, terms, _, _).
TEST(GlslTwins, CsmBasisAndReconstructionMatchTheirCppTwins) {
  test::TwinRandom r(6);
  std::vector<TwinCase> cases;
  for (int terms = 1; terms <= kMaxCsmTerms; ++terms)
    for (glm::vec4 a : {glm::vec4(0, 0, 1, 0), glm::vec4(1, 1, 1, 0), glm::vec4(0.5f, 0.5f, 0.5f, 0), glm::vec4(0, 1, 0.5f, 0)})
      for (float d : {0.f, 1.f, a.x, a.y, 0.5f * (a.x + a.y)}) cases.push_back({a, glm::vec4(d, float(terms), 0, 0)});
  while (cases.size() < 12000) {
    const float z0 = r.uniform(0, 1), z1 = r.uniform(0, 1);
    // The receiver near the occluders (where the series ramps) half of the time, anywhere otherwise.
    const float d = r.uniform(0, 1) < 0.5f ? std::clamp(z0 + r.uniform(-0.1f, 0.1f), 0.f, 1.f) : r.uniform(0, 1);
    cases.push_back({glm::vec4(z0, z1, r.uniform(0, 1), 0), glm::vec4(d, float(1 + int(r.uniform(0, 8)) % 8), 0, 0)});
  }
  const std::string helper =
      "float twin_csm(vec4 a, vec4 b) { vec4 layers[CSM_MAX_TERMS / 2]; for (int l = 0; l < CSM_MAX_TERMS / 2; ++l) "
      "layers[l] = a.z * csm_basis_layer(a.x, l) + (1.0 - a.z) * csm_basis_layer(a.y, l); "
      "return csm_visibility(layers, b.x, int(b.y)); }";
  const auto gpu = test::run_glsl_twin({kCsm, "twin_csm(a, b), 0.0, 0.0, 0.0", {}, helper}, cases);
  // The basis alone, layer by layer: a.x's layer int(b.y) - 1 mod 4.
  const auto gpu_basis = test::run_glsl_twin({kCsm, "csm_basis_layer(a.x, (int(b.y) - 1) % 4)"}, cases);
  std::vector<glm::vec4> cpu, cpu_basis;
  std::vector<double> tolerance;
  for (const TwinCase& c : cases) {
    const int terms = int(c.b.y);
    const std::vector<float> b0 = csm_basis(c.a.x, kMaxCsmTerms), b1 = csm_basis(c.a.y, kMaxCsmTerms);
    std::vector<float> mixed(b0.size());
    for (std::size_t i = 0; i < b0.size(); ++i) mixed[i] = c.a.z * b0[i] + (1.f - c.a.z) * b1[i];
    cpu.push_back(glm::vec4(csm_visibility(mixed, c.b.x, terms), 0, 0, 0));
    const std::size_t l = std::size_t((terms - 1) % 4);
    cpu_basis.push_back(glm::vec4(b0[4 * l], b0[4 * l + 1], b0[4 * l + 2], b0[4 * l + 3]));
    // Each mixed basis value is off by at most kTrig (w + (1 - w) = 1) plus the mix's two
    // roundings (2 ulp of 1), and each term b.x cos(c d) - b.y sin(c d) (|b| <= 1) by twice
    // (kTrig + 2 ulp) per product plus 2 ulp, times 2 / c_k; the sum of up to 9 terms of at most
    // 1.2 rounds 9 times (an ulp of 2 each); the doubling is exact and the clamp only narrows.
    double sum = 9 * 2 * 0x1p-23;
    for (int k = 1; k <= terms; ++k) sum += 2.0 / csm_coefficient(k) * (2 * (2 * kTrig + 4 * 0x1p-23) + 2 * 0x1p-23);
    tolerance.push_back(2 * sum);
  }
  auto describe = [&](std::size_t i) { return describe4(cases, i); };
  EXPECT_TRUE(test::twins_agree(gpu_basis, cpu_basis, 4, {kTrig, 0}, describe)) << "the basis";
  EXPECT_TRUE(test::twins_agree(gpu, cpu, 1, [&](std::size_t i) { return test::TwinTolerance{tolerance[i], 0}; }, describe))
      << "the reconstruction";
}

// The Hamburger reconstruction (and the 16-bit map's unoptimise) on the moments a filter leaves:
// 1 to 4 depths with random weights, the receiver near one of them half of the time (where the
// reconstruction ramps) and anywhere otherwise; half of the cases through the 16-bit map
// (msm_optimize, rounded to 16-bit steps, read back by msm_unoptimize on each side) with its
// moment bias, half as the 32-bit map stores them with its own. The edge cases are one depth
// alone, where the Hankel matrix without the bias is singular (the moment bias is what keeps the
// result defined there), and the ends of the depth range. a = the moments (stored, if 16-bit),
// b = (d, bias, 16-bit, _).
// The tolerance: the reconstruction is ill-conditioned where the moments are nearly those of
// one depth (the bias, 3e-5 or 3e-7, is all that keeps d22 from 0), so its float result depends
// on the rounding of every step, which GLSL does not fix (division 2.5 ulp, fused
// multiply-adds). Each rounding is a relative perturbation of a few ulps of an input of the
// step; the result's sensitivity to that is estimated case by case by running the C++ twin on
// 16 copies of the inputs, each component perturbed by up to 8 ulps, and the tolerance is twice
// the largest change seen, plus 2^-20. An estimate, not a bound: where the sensitivity is small
// (the well-conditioned cases, most of them) the GPU must agree closely. Without the moment bias
// in the GLSL, one-depth cases of both maps differ from the twin by up to 1 (a receiver just
// behind its one occluder read as lit).
TEST(GlslTwins, MsmHamburgerMatchesItsCppTwin) {
  test::TwinRandom r(64);
  const auto stored16 = [](glm::vec4 b) {
    glm::vec4 s = msm_optimize(b);
    for (int k = 0; k < 4; ++k) s[k] = std::round(std::clamp(s[k], 0.f, 1.f) * 65535.f) / 65535.f;
    return s;
  };
  std::vector<TwinCase> cases;
  const auto add = [&](glm::vec4 moments, float d, bool sixteen) {
    cases.push_back({sixteen ? stored16(moments) : moments,
                     glm::vec4(d, sixteen ? kMsmMomentBias16 : kMsmMomentBias32, sixteen ? 1.f : 0.f, 0)});
  };
  for (float z : {0.f, 0.05f, 0.2f, 0.37f, 0.5f, 0.63f, 0.81f, 0.95f, 1.f})
    for (float dd : {-1e-2f, -1e-3f, -1e-4f, 0.f, 1e-4f, 1e-3f, 3e-3f, 1e-2f, 0.1f})
      for (bool sixteen : {false, true}) add(msm_moments(z), std::clamp(z + dd, 0.f, 1.f), sixteen);
  // A receiver exactly at its one caster's depth: in 32 bits the quadratic's leading coefficient
  // rounds to 0 for one z in twelve of these (its guard).
  for (int i = 0; i <= 2000; ++i) add(msm_moments(i / 2000.f), i / 2000.f, false);
  while (cases.size() < 12000) {
    const int n = 1 + int(r.uniform(0, 4)) % 4;
    glm::dvec4 b(0);
    double total = 0;
    std::vector<float> z(static_cast<std::size_t>(n)), w(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) z[std::size_t(i)] = r.uniform(0, 1), w[std::size_t(i)] = r.uniform(0.05f, 1), total += w[std::size_t(i)];
    for (int i = 0; i < n; ++i) b += double(w[std::size_t(i)]) / total * glm::dvec4(msm_moments(z[std::size_t(i)]));
    const float d = r.uniform(0, 1) < 0.5f ? std::clamp(z[0] + r.uniform(-0.02f, 0.02f), 0.f, 1.f) : r.uniform(0, 1);
    add(glm::vec4(b), d, r.uniform(0, 1) < 0.5f);
  }
  const auto gpu = test::run_glsl_twin(
      {{"06_shadows/shaders/msm_math.glsl"}, "msm_hamburger(b.z > 0.5 ? msm_unoptimize(a) : a, b.x, b.y), 0.0, 0.0, 0.0"}, cases);
  const auto twin = [](glm::vec4 a, glm::vec4 b) {
    return msm_hamburger(b.z > 0.5f ? msm_unoptimize(a) : a, b.x, b.y);
  };
  std::vector<glm::vec4> cpu;
  std::vector<double> tolerance;
  double largest = 0;
  for (const TwinCase& c : cases) {
    const float v = twin(c.a, c.b);
    cpu.push_back(glm::vec4(v, 0, 0, 0));
    double spread = 0;
    for (int k = 0; k < 16; ++k) {
      glm::vec4 a = c.a, b = c.b;
      for (int i = 0; i < 4; ++i) a[i] *= 1.f + r.uniform(-8, 8) * 0x1p-23f;
      b.x *= 1.f + r.uniform(-8, 8) * 0x1p-23f;
      spread = std::max(spread, double(std::abs(twin(a, b) - v)));
    }
    tolerance.push_back(2 * spread + 0x1p-20);
    largest = std::max(largest, tolerance.back());
  }
  std::size_t loose = 0;
  for (double t : tolerance) loose += t > 0.01;
  std::printf("msm: tolerance above 0.01 in %zu of %zu cases (largest %.3g)\n", loose, cases.size(), largest);
  // Near one depth the float reconstruction degenerates even with the bias (d22 or d33_d22
  // rounds to 0 or below, or the quadratic to a line): the guards of msm_hamburger give the
  // limit's visibility there, never NaN (without them the C++ twin was NaN in ~2 % of these).
  std::size_t undefined = 0;
  for (std::size_t i = 0; i < cases.size(); ++i)
    if (!std::isfinite(cpu[i].x) || cpu[i].x < 0.f || cpu[i].x > 1.f) {
      if (undefined++ < 5) ADD_FAILURE() << "the C++ twin gives " << cpu[i].x << " for " << describe4(cases, i);
    }
  EXPECT_EQ(undefined, 0u) << "cases where the C++ twin is not a visibility in [0, 1]";
  for (std::size_t i = 0; i < cases.size(); ++i) {
    ASSERT_TRUE(std::isfinite(gpu[i].x) && gpu[i].x >= 0.f && gpu[i].x <= 1.f) << describe4(cases, i) << " gives " << gpu[i].x;
  }
  EXPECT_TRUE(test::twins_agree(gpu, cpu, 1, [&](std::size_t i) { return test::TwinTolerance{tolerance[i], 0}; },
                                [&](std::size_t i) { return describe4(cases, i); }));
}

// VSM's lookup: Chebyshev's bound with P_min's rescale (filtered_math.glsl against
// chebyshev_upper_bound and reduce_light_bleeding). The two twins run the same correctly rounded
// + - * except where GLSL may fuse a product into a sum (one rounding less: at most half an ulp
// of m.x^2 in the variance, of d^2 in the denominator) and its divisions (2.5 ulp, C++ 0.5). So
// p_max differs by at most p_max (ulp/2 m.x^2 / v + ulp/2 d^2 / (v + d^2) + 3 ulp), with v the
// floored variance, and the rescaled value by that plus an ulp of (p_max + P_min), over
// (1 - P_min), plus its own 3 ulp. Cases: moments of two depths mixed (the bound's own domain),
// receivers in front of, at and behind the mean, P_min 0 to 0.9, and the variance's floor.
TEST(GlslTwins, VsmWithPminMatchesItsCppTwin) {
  test::TwinRandom r(65);
  std::vector<TwinCase> cases;
  while (cases.size() < 12000) {
    const float z0 = r.uniform(0, 1), z1 = r.uniform(0, 1), w = r.uniform(0, 1);
    const glm::vec2 m(w * z0 + (1 - w) * z1, w * z0 * z0 + (1 - w) * z1 * z1);
    float z = cases.size() % 5 == 0 ? m.x : r.uniform(0, 1);
    if (cases.size() % 7 == 0) z = std::nextafter(m.x, 2.f);
    const float p_min = cases.size() % 3 == 0 ? 0.f : r.uniform(0, 0.9f);
    const float min_variance = cases.size() % 2 == 0 ? 1e-6f : r.log_uniform(1e-7f, 1e-3f);
    cases.push_back({glm::vec4(m, z, 0), glm::vec4(min_variance, p_min, 0, 0)});
  }
  const auto gpu = test::run_glsl_twin({{"06_shadows/shaders/filtered_math.glsl"}, "vsm_lit_fraction(a.xy, a.z, b.x, b.y), 0.0, 0.0, 0.0"}, cases);
  std::vector<glm::vec4> cpu;
  std::vector<double> tolerance;
  for (const TwinCase& c : cases) {
    const glm::vec2 m(c.a);
    const float p_max = chebyshev_upper_bound(m, c.a.z, c.b.x);
    const float v = reduce_light_bleeding(p_max, c.b.y);
    cpu.push_back(glm::vec4(v, 0, 0, 0));
    const double variance = std::max(double(m.y) - double(m.x) * m.x, double(c.b.x)), d = double(c.a.z) - m.x;
    const double dp = p_max * (test::ulps(0.5) * m.x * m.x / variance + test::ulps(0.5) * d * d / (variance + d * d) + test::ulps(3));
    tolerance.push_back((dp + test::ulps(1) * (p_max + c.b.y)) / (1 - c.b.y) + test::ulps(3) * v);
  }
  EXPECT_TRUE(test::twins_agree(gpu, cpu, 1, [&](std::size_t i) { return test::TwinTolerance{tolerance[i], 0}; },
                                [&](std::size_t i) { return describe4(cases, i); }));
}

// ESM's lookup: clamp(exp(min(L - c d, 0)), 0, 1) (filtered_math.glsl against
// esm_visibility_log). L - c d: GLSL may fuse it (half an ulp of c d apart), the subtraction an
// ulp of the larger term; exp's argument error x carries into the result as a relative x, and
// GLSL's exp is (3 + 2 |x|) ulp, the C++ one an ulp; a denormal result may be flushed to 0. Cases: c 1 to 300 (log-uniform, past fp32's
// overflow of exp(c z) at c = 88), receivers in front of and behind L / c.
TEST(GlslTwins, EsmLookupMatchesItsCppTwin) {
  test::TwinRandom r(66);
  std::vector<TwinCase> cases;
  while (cases.size() < 12000) {
    const float c = r.log_uniform(1, 300), occluder = r.uniform(0, 1);
    const float l = c * occluder;  // one occluder's log value; a filtered one lies below the largest
    const float z = cases.size() % 5 == 0 ? occluder : std::clamp(occluder + r.uniform(-0.1f, 0.3f), 0.f, 1.f);
    cases.push_back({glm::vec4(l, c, z, 0)});
  }
  const auto gpu = test::run_glsl_twin({{"06_shadows/shaders/filtered_math.glsl"}, "esm_lit_fraction(a.x, a.y, a.z), 0.0, 0.0, 0.0"}, cases);
  std::vector<glm::vec4> cpu;
  std::vector<double> tolerance;
  for (const TwinCase& c : cases) {
    const float v = esm_visibility_log(c.a.x, c.a.y, c.a.z);
    cpu.push_back(glm::vec4(v, 0, 0, 0));
    const double cz = double(c.a.y) * c.a.z, x = std::min(double(c.a.x) - cz, 0.0);
    const double argument = test::ulps(0.5) * cz + test::ulps(1) * std::max(std::abs(double(c.a.x)), cz);
    tolerance.push_back(v * (argument + test::ulps(3 + 2 * std::abs(x)) + test::ulps(1)) + 0x1p-126);  // denormals flushed
  }
  EXPECT_TRUE(test::twins_agree(gpu, cpu, 1, [&](std::size_t i) { return test::TwinTolerance{tolerance[i], 0}; },
                                [&](std::size_t i) { return describe4(cases, i); }));
}

// The pre-filter's moments and the 16-bit map's optimised form (msm_math.glsl's msm_moments and
// msm_optimize against shadow_math.h's). The moments: z^2 = z z, z^3 = z^2 z, z^4 = z^2 z^2 are
// each one product, correctly rounded on both sides (GLSL 4.50's * is), of the same floats: equal,
// except that a GPU may flush a denormal result to 0 (2^-126 absolutely). The optimised map: each
// component sum_j M_kj b_j (+ the offset for x) is four products and three or four additions, in
// any order and fused or not on either side: at most 5 u sum_j |M_kj b_j| (+ |offset|) from the
// exact value on each side (the sum's classic bound, gamma_n <= n u + O(u^2)), so 10 u of that
// apart. Cases: depths over [0, 1] (their moments), the ends, tiny and denormal depths, and
// moments of 2 to 8 depths mixed by random weights (what the map's filtered texels hold).
TEST(GlslTwins, MsmMomentsAndOptimizeMatchTheirCppTwins) {
  test::TwinRandom r(70);
  std::vector<TwinCase> depths;
  for (float z : {0.f, 1.f, 0.5f, std::nextafter(1.f, 0.f), 1e-10f, 1e-20f, 1e-30f, 0x1p-126f, 1e-3f, 0.999f})
    depths.push_back({glm::vec4(z, 0, 0, 0)});
  while (depths.size() < 12000) depths.push_back({glm::vec4(depths.size() % 3 == 0 ? r.log_uniform(1e-6f, 1) : r.uniform(0, 1), 0, 0, 0)});
  const std::vector<std::string> kMsm = {"06_shadows/shaders/msm_math.glsl"};
  const auto gpu_moments = test::run_glsl_twin({kMsm, "msm_moments(a.x)"}, depths);
  std::vector<glm::vec4> cpu_moments;
  for (const TwinCase& c : depths) cpu_moments.push_back(msm_moments(c.a.x));
  EXPECT_TRUE(test::twins_agree(gpu_moments, cpu_moments, 4, test::TwinTolerance{0x1p-126, 0},
                                [&](std::size_t i) { return describe4(depths, i); }))
      << "the moments";

  std::vector<TwinCase> moments;
  for (const TwinCase& c : depths) {
    if (moments.size() % 2 == 0) {
      moments.push_back({msm_moments(c.a.x)});
      continue;
    }
    const int n = 2 + int(r.uniform(0, 7)) % 7;
    std::vector<float> w(static_cast<std::size_t>(n));
    float total = 0;
    for (float& x : w) x = r.uniform(0.05f, 1), total += x;
    glm::vec4 b(0);
    for (float x : w) b += x / total * msm_moments(r.uniform(0, 1));
    moments.push_back({b});
  }
  const auto gpu = test::run_glsl_twin({kMsm, "msm_optimize(a)"}, moments);
  // glm's mat4 takes columns: row k of the map is (m[0][k], m[1][k], m[2][k], m[3][k]).
  const glm::vec4 zero_in = msm_optimize(glm::vec4(0));
  const float offset = zero_in.x;
  glm::mat4 m(0);
  for (int j = 0; j < 4; ++j) {
    glm::vec4 e(0);
    e[j] = 1;
    m[j] = msm_optimize(e) - zero_in;  // column j, within 2 u of 0.036 (the offset's rounding)
  }
  std::vector<glm::vec4> cpu;
  std::vector<double> tolerance;
  for (const TwinCase& c : moments) {
    cpu.push_back(msm_optimize(c.a));
    double t = 0;
    for (int k = 0; k < 4; ++k) {
      double sum = k == 0 ? std::abs(double(offset)) : 0;
      for (int j = 0; j < 4; ++j) sum += std::abs(double(m[j][k]) * c.a[j]);
      t = std::max(t, 10 * kU * 1.01 * sum);  // 1.01: the columns' entries (>= 0.1) within 1 % of the map's
    }
    tolerance.push_back(t + 0x1p-126);
  }
  EXPECT_TRUE(test::twins_agree(gpu, cpu, 4, [&](std::size_t i) { return test::TwinTolerance{tolerance[i], 0}; },
                                [&](std::size_t i) { return describe4(moments, i); }))
      << "the optimised map";
}

// ESM's pre-filter, log-sum-exp about the largest value (filtered_math.glsl's esm_log_sum_term
// and esm_log_sum, in shadow_filter.frag's two passes over the taps, against esm_filter_log):
// L = l_max + log(S), S = sum_i w_i exp(l_i - l_max). l_max is exact on both sides, l_i - l_max
// rounds the same (correctly rounded, same floats). Each term t_i differs by exp's allowance
// (GLSL (3 + 2 |x|) ulp, x = l_i - l_max; the C++ expf an ulp) and the product's rounding (half
// an ulp each side, or none if fused); the sum of up to 8 terms rounds 7 times on each side (7 u S
// each). So |dS| / S <= max_i ((4 + 2 |x_i|) ulp + 2 u) + 14 u, plus 2^-126 per term for flushed
// denormals, over S. log turns that into an absolute error of |dS| / S; GLSL's log adds 2^-21
// absolutely for S in [0.5, 2] and 3 ulp of |log S| outside it, the C++ logf an ulp; the final
// addition rounds each side (half an ulp of |L| each). Cases: 1 to 8 taps (unused taps weigh 0),
// box weights 1 / n as the pre-filter's half of the time and random normalised ones otherwise, c 1
// to 300 (log-uniform) times depths in [0, 1]; taps all equal (S = 1, log S = 0), one tap, and
// taps c apart (the exponent's underflow).
TEST(GlslTwins, EsmFilterLogMatchesItsCppTwin) {
  test::TwinRandom r(71);
  std::vector<TwinCase> cases;
  const auto add = [&](const std::vector<float>& l, std::vector<float> w) {
    TwinCase c{};
    for (std::size_t i = 0; i < 8; ++i) {
      const float v = i < l.size() ? l[i] : l[0], weight = i < w.size() ? w[i] : 0.f;
      (i < 4 ? c.a : c.b)[int(i % 4)] = v;
      (i < 4 ? c.c : c.d)[int(i % 4)] = weight;
    }
    cases.push_back(c);
  };
  for (float c : {1.f, 10.f, 80.f, 88.f, 89.f, 300.f})
    for (int n = 1; n <= 8; ++n) {
      add(std::vector<float>(std::size_t(n), 0.5f * c), std::vector<float>(std::size_t(n), 1.f / float(n)));  // all equal
      std::vector<float> apart(std::size_t(n), 0.f);
      apart[0] = c;  // one tap at z = 1, the others at z = 0
      add(apart, std::vector<float>(std::size_t(n), 1.f / float(n)));
      add({c}, {1.f});
      add({0.f}, {1.f});
    }
  while (cases.size() < 12000) {
    const int n = 1 + int(r.uniform(0, 8)) % 8;
    const float c = r.log_uniform(1, 300);
    std::vector<float> l(static_cast<std::size_t>(n)), w(static_cast<std::size_t>(n));
    const float centre = r.uniform(0, 1), spread = r.uniform(0, 1) < 0.5f ? 0.02f : 1.f;
    float total = 0;
    for (int i = 0; i < n; ++i) {
      l[std::size_t(i)] = c * std::clamp(centre + r.uniform(-spread, spread), 0.f, 1.f);
      w[std::size_t(i)] = cases.size() % 2 == 0 ? 1.f / float(n) : r.uniform(0.05f, 1);
      total += w[std::size_t(i)];
    }
    if (cases.size() % 2 == 1)
      for (float& x : w) x /= total;
    add(l, w);
  }
  const std::string helper =
      "float twin_esm_filter(vec4 a, vec4 b, vec4 c, vec4 d) { float l_max = -3.4e38; "
      "for (int i = 0; i < 4; ++i) l_max = max(l_max, a[i]); for (int i = 0; i < 4; ++i) l_max = max(l_max, b[i]); "
      "float sum = 0.0; for (int i = 0; i < 4; ++i) sum += esm_log_sum_term(a[i], l_max, c[i]); "
      "for (int i = 0; i < 4; ++i) sum += esm_log_sum_term(b[i], l_max, d[i]); return esm_log_sum(l_max, sum); }";
  const auto gpu = test::run_glsl_twin(
      {{"06_shadows/shaders/filtered_math.glsl"}, "twin_esm_filter(a, b, c, d), 0.0, 0.0, 0.0", {}, helper}, cases);
  std::vector<glm::vec4> cpu;
  std::vector<double> tolerance;
  for (const TwinCase& c : cases) {
    std::vector<float> l, w;
    for (int i = 0; i < 8; ++i) l.push_back((i < 4 ? c.a : c.b)[i % 4]), w.push_back((i < 4 ? c.c : c.d)[i % 4]);
    const float filtered = esm_filter_log(l, w);
    cpu.push_back(glm::vec4(filtered, 0, 0, 0));
    const double l_max = *std::max_element(l.begin(), l.end());
    double s = 0, ds = 0;
    for (std::size_t i = 0; i < 8; ++i) {
      const double x = double(l[i]) - l_max, t = w[i] * std::exp(x);
      s += t;
      ds += t * (test::ulps(4 + 2 * std::abs(x)) + 2 * kU) + 0x1p-126;
    }
    ds += 14 * kU * s;
    const double log_s = std::log(s);
    const double log_error = (s >= 0.5 && s <= 2 ? 0x1p-21 : test::ulps(3) * std::abs(log_s)) + test::ulps(1) * std::abs(log_s);
    tolerance.push_back(ds / s + log_error + 2 * kU * std::abs(double(filtered)));
  }
  EXPECT_TRUE(test::twins_agree(gpu, cpu, 1, [&](std::size_t i) { return test::TwinTolerance{tolerance[i], 0}; },
                                [&](std::size_t i) { return describe4(cases, i); }));
}

// cube_face_coords is OpenGL's cube map table, which the depth pass's face matrices follow
// (CubeMath.TheDepthPassDrawsEachDirectionWhereTheLookupReadsIt); here it is held to the sampler
// itself: point_visibility()'s lookup, a samplerCubeArray read with a direction, on a map whose
// texels hold their own face and centre. The texel read must be the one holding cube_face_coords'
// (s, t), to half a texel plus the sampler's sub-texel precision (taken as Vulkan's minimum, 4
// bits: a sixteenth of a texel) and the GPU's division sc / ma (2.5 ulp, far below). Where two
// components tie for the major axis the specification lets the implementation pick either face.
TEST(GlslTwins, CubeFaceCoordsNameTheTexelTheSamplerReads) {
  constexpr int kN = 16, kLayers = 2;
  gl::Texture cube(GL_TEXTURE_CUBE_MAP_ARRAY);
  glTextureStorage3D(cube.id(), 1, GL_RGBA32F, kN, kN, 6 * kLayers);
  for (int layer = 0; layer < kLayers; ++layer)
    for (int face = 0; face < 6; ++face) {
      std::vector<glm::vec4> texels;
      for (int j = 0; j < kN; ++j)  // rows from t = 0 up
        for (int i = 0; i < kN; ++i) texels.push_back({float(face), (i + 0.5f) / kN, (j + 0.5f) / kN, float(layer)});
      glTextureSubImage3D(cube.id(), 0, 0, 0, 6 * layer + face, kN, kN, 1, GL_RGBA, GL_FLOAT, texels.data());
    }
  glTextureParameteri(cube.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(cube.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindTextureUnit(3, cube.id());

  test::TwinRandom r(61);
  std::vector<TwinCase> cases;
  for (int axis = 0; axis < 3; ++axis)
    for (float sign : {1.f, -1.f}) {
      glm::vec3 d(0);
      d[axis] = sign;
      cases.push_back({glm::vec4(d, 0)});
      d[(axis + 1) % 3] = 0.999f * sign;  // next to an edge
      cases.push_back({glm::vec4(d, 1)});
      d[(axis + 2) % 3] = -0.999f;        // next to a corner
      cases.push_back({glm::vec4(d, 0)});
    }
  cases.push_back({glm::vec4(1, 1, 0.3f, 0)});  // ties: either face
  cases.push_back({glm::vec4(-1, -1, -1, 1)});
  while (cases.size() < 12000) {
    const glm::vec3 d = r.unit() * r.log_uniform(1e-3f, 1e3f);
    cases.push_back({glm::vec4(d, float(int(r.uniform(0, 2)) % 2))});
  }
  const auto gpu = test::run_glsl_twin(
      {{}, "textureLod(twin_cube, vec4(a.xyz, a.w), 0.0)", {}, "layout(binding = 3) uniform samplerCubeArray twin_cube;"}, cases);
  glBindTextureUnit(3, 0);
  std::size_t failed = 0, ties = 0;
  double worst = 0;
  const double allowed = 0.5 / kN + 1.0 / 16 / kN;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const glm::vec3 d(cases[i].a);
    const CubeCoords c = cube_face_coords(d);
    const glm::vec3 m = glm::abs(d);
    const float major = std::max({m.x, m.y, m.z});
    const int at_major = (m.x == major) + (m.y == major) + (m.z == major);
    if (at_major > 1) {  // a tie: the face is the implementation's choice, but a face of the tie
      ++ties;
      const int face = int(gpu[i].x);
      EXPECT_TRUE(m[face / 2] == major) << "a tie read face " << face << " for " << test::str(cases[i].a);
      continue;
    }
    const double e = std::max(std::abs(double(gpu[i].y) - c.st.x), std::abs(double(gpu[i].z) - c.st.y));
    worst = std::max(worst, e);
    const bool ok = int(gpu[i].x) == int(c.face) && e <= allowed && gpu[i].w == cases[i].a.w;
    if (!ok && failed++ < 5)
      ADD_FAILURE() << "direction " << test::str(cases[i].a) << ": the sampler read face " << gpu[i].x << " texel centre ("
                    << gpu[i].y << ", " << gpu[i].z << "), cube_face_coords says face " << int(c.face) << " at ("
                    << c.st.x << ", " << c.st.y << ")";
  }
  std::printf("  %zu directions (%zu ties); (s, t) at most %.4f texels from the centre read, allowed %.4f\n", cases.size(),
              ties, worst * kN, allowed * kN);
  EXPECT_EQ(failed, 0u);
}

// lookup_math.glsl: where a lookup reads.

// PCF's receiver plane (receiver_plane_gradient against shadow_math.h's). The light's view is a
// rotation (random directions, as fit_light_frustum's lookAt makes them); n = M w, each
// component a three-term dot product: at most 3 u of sum_j |M_kj w_j| (S_k) on either side, fused
// or not. n.x / nz, * extent, / depth_range: GLSL's two divisions 2.5 ulp each and the product's
// half, 5.5 ulp, C++'s 1.5, so 7 ulp of the gradient; the max is exact and moves nz by no more
// than n.z moves. To first order (the second-order terms are below 2^-40 relatively):
//   |dg_k| <= E_k / R (6 u S_k / nz + |n_k| 6 u S_z / nz^2) + 7 ulp |g_k|.
// Cases: random normals (half facing the light), the grazing ones near the 20:1 floor (n.z just
// above and below 0.05), the floor exactly, normals facing away, along the light and across it;
// extents 1 to 1000 m, depth ranges 1 to 2000 m, log-uniform.
TEST(GlslTwins, ReceiverPlaneGradientMatchesItsCppTwin) {
  test::TwinRandom r(67);
  std::vector<TwinCase> cases;
  std::vector<LightFrustum> frusta;
  const auto add = [&](glm::vec3 direction, glm::vec3 view_normal, bool normal_in_view) {
    LightFrustum f;
    const glm::vec3 up = std::abs(direction.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    f.view = glm::lookAt(glm::vec3(0), direction, up);
    const float ex = r.log_uniform(1, 1000), ey = r.log_uniform(1, 1000), z0 = r.uniform(-500, 0);
    f.box_min = glm::vec3(-0.5f * ex, -0.5f * ey, z0 - r.log_uniform(1, 2000));
    f.box_max = glm::vec3(0.5f * ex, 0.5f * ey, z0);
    // A normal given in the light's view space is taken back to the world by the transpose.
    const glm::vec3 w = normal_in_view ? glm::transpose(glm::mat3(f.view)) * view_normal : view_normal;
    const glm::mat3 m(f.view);
    const glm::vec2 extent(f.box_max - f.box_min);
    cases.push_back({glm::vec4(m[0], extent.x), glm::vec4(m[1], extent.y), glm::vec4(m[2], f.depth_range()), glm::vec4(w, 0)});
    frusta.push_back(f);
  };
  for (float nz : {1.f, 0.5f, 0.2f, 0.1f, 0.0501f, 0.05f, 0.0499f, 0.01f, 0.f, -0.3f, -1.f})
    for (float phi : {0.f, 0.7f, 1.5707964f, 2.9f, 4.4f}) {
      const float s = std::sqrt(std::max(0.f, 1 - nz * nz));
      add(r.unit(), glm::vec3(s * std::cos(phi), s * std::sin(phi), nz), true);
    }
  while (cases.size() < 12000) {
    glm::vec3 n = r.unit();
    if (cases.size() % 2 == 0) n.z = std::abs(n.z);  // facing the light
    if (cases.size() % 5 == 0) n = glm::normalize(glm::vec3(n.x, n.y, r.uniform(0.03f, 0.2f)));  // grazing
    add(r.unit(), n, true);
  }
  const auto gpu = test::run_glsl_twin(
      {{"06_shadows/shaders/lookup_math.glsl"}, "receiver_plane_gradient(mat3(a.xyz, b.xyz, c.xyz), d.xyz, vec2(a.w, b.w), c.w), 0.0, 0.0"},
      cases);
  std::vector<glm::vec4> cpu;
  std::vector<double> tolerance;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const TwinCase& c = cases[i];
    const glm::vec2 g = receiver_plane_gradient(frusta[i], glm::vec3(c.d));
    cpu.push_back(glm::vec4(g, 0, 0));
    const glm::dmat3 m(glm::dvec3(c.a), glm::dvec3(c.b), glm::dvec3(c.c));
    const glm::dvec3 w(c.d), n = m * w;
    double sum[3];
    for (int k = 0; k < 3; ++k) sum[k] = std::abs(m[0][k] * w.x) + std::abs(m[1][k] * w.y) + std::abs(m[2][k] * w.z);
    const double nz = std::max(n.z, 0.05), extent[2] = {c.a.w, c.b.w}, range = c.c.w;
    double t = 0;
    for (int k = 0; k < 2; ++k)
      t = std::max(t, extent[k] / range * (6 * kU * sum[k] / nz + std::abs(n[k]) * 6 * kU * sum[2] / (nz * nz)) +
                          test::ulps(7) * std::abs(n[k] / nz * extent[k] / range));
    tolerance.push_back(t);
  }
  EXPECT_TRUE(test::twins_agree(gpu, cpu, 2, [&](std::size_t i) { return test::TwinTolerance{tolerance[i], 0}; },
                                [&](std::size_t i) { return describe4(cases, i); }));
}

// The cascade choice (choose_cascade against shadow_math.h's). Which cascade: both compare the
// same floats (depth < far), so it must be equal. The blend weight w = (depth - (F - L)) / L,
// L = band (F - P): L rounds twice (2 u of L), F - L once more (u |F - L|), the numerator once
// more (u |N|, |N| / L = w), the division 2.5 ulp (5 u) in GLSL, u in C++; the clamp moves
// nothing apart. Per side |dw| <= 2 u + u |F - L| / L + (1 + 2 + division) u w, both sides:
//   4 u + 2 u |F - L| / L + 12 u w   (w taken at most 2: beyond 1 both clamp to 1).
// Cases: 1 to 4 cascades (the chapter's practical splits and random ones), bands 0 to 1; depths
// anywhere from before the near plane to past the last split, and on every split, the band's
// start and their neighbouring floats.
TEST(GlslTwins, CascadeChoiceMatchesItsCppTwin) {
  test::TwinRandom r(68);
  std::vector<TwinCase> cases;
  std::vector<std::vector<float>> split_sets;
  const auto add = [&](const std::vector<float>& splits, float depth, float band) {
    glm::vec4 far(0);
    for (std::size_t i = 1; i < splits.size(); ++i) far[int(i) - 1] = splits[i];
    cases.push_back({far, glm::vec4(depth, splits[0], float(splits.size() - 1), band)});
    split_sets.push_back(splits);
  };
  const auto random_splits = [&]() {
    const int count = 1 + int(r.uniform(0, 4)) % 4;
    const float near = r.log_uniform(0.01f, 1.f), far = near * r.log_uniform(2, 10000);
    if (r.uniform(0, 1) < 0.5f) return cascade_splits(count, near, far, r.uniform(0, 1));
    std::vector<float> z{near};
    for (int i = 0; i < count; ++i) z.push_back(z.back() * r.log_uniform(1.01f, 20));
    return z;
  };
  while (cases.size() < 4000) {  // the edges
    const std::vector<float> z = random_splits();
    const float band = cases.size() % 8 == 0 ? 0.f : cases.size() % 8 == 1 ? 1.f : r.uniform(0, 0.5f);
    for (std::size_t i = 0; i < z.size(); ++i) {
      for (float d : {z[i], std::nextafter(z[i], 0.f), std::nextafter(z[i], 1e9f)}) add(z, d, band);
      if (i == 0) continue;
      const float start = z[i] - band * (z[i] - z[i - 1]);  // where the band begins
      for (float d : {start, std::nextafter(start, 0.f), std::nextafter(start, 1e9f)}) add(z, d, band);
    }
    add(z, 0.f, band);
    add(z, -1.f, band);
  }
  while (cases.size() < 16000) {
    const std::vector<float> z = random_splits();
    add(z, r.log_uniform(0.5f * z.front(), 1.5f * z.back()), cases.size() % 4 == 0 ? 0.f : r.uniform(0, 1));
  }
  const std::string helper =
      "vec2 twin_cascade(vec4 a, vec4 b) { CascadeChoice c = choose_cascade(b.x, a, b.y, int(b.z), b.w); "
      "return vec2(float(c.cascade), c.next_weight); }";
  const auto gpu = test::run_glsl_twin({{"06_shadows/shaders/lookup_math.glsl"}, "twin_cascade(a, b), 0.0, 0.0", {}, helper}, cases);
  std::vector<glm::vec4> gpu_cascade, gpu_weight, cpu_cascade, cpu_weight;
  std::vector<double> tolerance;
  std::size_t blended = 0, beyond = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const std::vector<float>& z = split_sets[i];
    const float depth = cases[i].b.x, band = cases[i].b.w;
    const CascadeChoice c = choose_cascade(depth, z, band);
    gpu_cascade.push_back(glm::vec4(gpu[i].x, 0, 0, 0));
    gpu_weight.push_back(glm::vec4(gpu[i].y, 0, 0, 0));
    cpu_cascade.push_back(glm::vec4(float(c.cascade), 0, 0, 0));
    cpu_weight.push_back(glm::vec4(c.next_weight, 0, 0, 0));
    blended += c.next_weight > 0.f && c.next_weight < 1.f;
    beyond += c.cascade < 0;
    double t = 0;
    if (c.cascade >= 0) {
      const std::size_t k = std::size_t(c.cascade);
      const double l = double(band) * (double(z[k + 1]) - z[k]), f = z[k + 1];
      if (l > 0) {
        const double w = std::min(std::abs((depth - (f - l)) / l), 2.0);
        t = 4 * kU + 2 * kU * std::abs(f - l) / l + 12 * kU * w;
      }
    }
    tolerance.push_back(t);
  }
  auto describe = [&](std::size_t i) { return "far splits " + test::str(cases[i].a) + " (depth, near, count, band) " + test::str(cases[i].b); };
  EXPECT_TRUE(test::twins_agree(gpu_cascade, cpu_cascade, 1, test::TwinTolerance{0, 0}, describe)) << "the cascade";
  EXPECT_TRUE(test::twins_agree(gpu_weight, cpu_weight, 1, [&](std::size_t i) { return test::TwinTolerance{tolerance[i], 0}; }, describe))
      << "the next cascade's weight";
  std::printf("  %zu cases, %zu inside a blend band, %zu beyond the last cascade\n", cases.size(), blended, beyond);
  EXPECT_GT(blended, 1000u);
  EXPECT_GT(beyond, 100u);
}

// The spots' atlas (spot_atlas_uv against spot_atlas.h's): half a texel, 0.5 / N, is 2.5 ulp in
// GLSL and 0.5 in C++ (6 u of it apart), 1 - h rounds on each side (u each), so the clamp's
// bounds, and the clamped (u, v), are at most 6 u h + 2 u apart; then corner + c side rounds twice
// on each side (fused or not): |d| <= side (6 u h + 2 u) + 2 u (|c| side + |result|). Cases: every
// tile of 1 to 16 spots in atlases of 64 to 4096 texels (powers of two and not), (u, v) over
// [-0.5, 1.5] (PCF's taps past the tile's edges), on the tile's edges, on the border texels'
// centres and their neighbouring floats.
TEST(GlslTwins, SpotAtlasUvMatchesItsCppTwin) {
  test::TwinRandom r(69);
  std::vector<TwinCase> cases;
  std::vector<AtlasTile> tiles;
  const int sizes[] = {64, 100, 128, 1000, 1024, 2048, 3000, 4096};
  std::size_t round = 0;
  while (cases.size() < 12000) {
    const int atlas = sizes[round % 8], count = 1 + int(round / 8) % kMaxSpotShadows;
    ++round;
    for (int index = 0; index < count; ++index) {
      const AtlasTile t = spot_atlas_tile(index, count, atlas);
      const float h = 0.5f / float(t.size);
      std::vector<float> edge{0.f, 1.f, h, 1 - h, std::nextafter(h, 0.f), std::nextafter(h, 1.f), std::nextafter(1 - h, 0.f),
                              std::nextafter(1 - h, 1.f), -1e-7f, 1 + 1e-7f};
      const float u = edge[std::size_t(index) % edge.size()], v = edge[std::size_t(index + round) % edge.size()];
      for (glm::vec2 uv : {glm::vec2(u, v), glm::vec2(r.uniform(-0.5f, 1.5f), r.uniform(-0.5f, 1.5f)),
                           glm::vec2(r.uniform(0, 1), r.uniform(0, 1))}) {
        cases.push_back({glm::vec4(t.corner, t.side, float(t.size)), glm::vec4(uv, 0, 0)});
        tiles.push_back(t);
      }
    }
  }
  const auto gpu = test::run_glsl_twin({{"06_shadows/shaders/lookup_math.glsl"}, "spot_atlas_uv(a.xyz, a.w, b.xy), 0.0, 0.0"}, cases);
  std::vector<glm::vec4> cpu;
  std::vector<double> tolerance;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const glm::vec2 uv = spot_atlas_uv(tiles[i], glm::vec2(cases[i].b));
    cpu.push_back(glm::vec4(uv, 0, 0));
    const double side = tiles[i].side, h = 0.5 / tiles[i].size;
    const double c = std::max(std::abs(double(cases[i].b.x)), std::abs(double(cases[i].b.y)));
    const double clamped = std::clamp(c, 0.0, 1.0);
    tolerance.push_back(side * (6 * kU * h + 2 * kU) + 2 * kU * (clamped * side + std::max(std::abs(uv.x), std::abs(uv.y))));
  }
  EXPECT_TRUE(test::twins_agree(gpu, cpu, 2, [&](std::size_t i) { return test::TwinTolerance{tolerance[i], 0}; },
                                [&](std::size_t i) { return describe4(cases, i); }));
}

// The sun's biases (slope_scaled_bias and normal_offset against shadow_math.h's). The clamp is
// exact; s2 = 1 - c c rounds twice in C++ and once if GLSL fuses it, each side within u (c^2 +
// s2) = u of the exact value, so 2 u apart; near c = 1 that is large against s2 itself, and
// sin = sqrt(s2) moves by at most min(sqrt(2 u), u / sin) from it. GLSL's sqrt is inherited from
// 1 / inversesqrt (2 + 2.5 ulp), C++'s correctly rounded (half an ulp): 5 ulp of sin more. tan =
// sin / c: that over c, plus the division's 2.5 + 0.5 ulp of tan; the cap at 10 moves nothing
// apart. The bias w (C + S tan): S tan, the sum and the product round once each on each side
// (fused or not), 6 u of w (C + S tan) apart, plus w S times tan's difference. The offset
// p + n (T w sin): T w rounds the same, (T w) sin half an ulp each side, so k = T w sin differs
// by T w dsin + 2 u k; each component p + n k rounds twice on each side (fused or not): |n| dk +
// 2 u |n k| + 2 u |result|. Cases: cosines over [-0.2, 1.2] (both clamps), near 1 (the
// ill-conditioned s2), at and around 1e-4 and 0, and where the cap begins (tan = 10, c =
// 1 / sqrt(101)); biases 0 to 2 texels, slopes 0 to 3, texels 0.1 mm to 10 m, positions within
// 100 m, unit normals.
TEST(GlslTwins, SlopeScaledBiasAndNormalOffsetMatchTheirCppTwins) {
  test::TwinRandom r(73);
  std::vector<float> cosines = {0.f, 1.f, -0.1f, 1.1f, 1e-4f, std::nextafter(1e-4f, 0.f), std::nextafter(1e-4f, 1.f), 5e-5f,
                                std::nextafter(1.f, 0.f), 1.f - 1e-6f, 1.f - 1e-4f, 0.5f, 0.70710677f};
  const float cap = 1.f / std::sqrt(101.f);
  for (float c : {cap, std::nextafter(cap, 0.f), std::nextafter(cap, 1.f), 0.0995f, 0.0996f}) cosines.push_back(c);
  std::vector<TwinCase> cases;
  for (float c : cosines)
    for (int k = 0; k < 20; ++k) {
      const glm::vec3 p(r.uniform(-100, 100), r.uniform(-100, 100), r.uniform(-100, 100));
      cases.push_back({glm::vec4(p, c), glm::vec4(r.unit(), r.log_uniform(1e-4f, 10)),
                       glm::vec4(k % 4 == 0 ? 0.f : r.uniform(0, 2), k % 5 == 0 ? 0.f : r.uniform(0, 3), r.uniform(0, 3), 0)});
    }
  while (cases.size() < 12000) {
    const float u = r.uniform(0, 1);
    const float c = u < 0.1f ? 1.f - r.log_uniform(1e-7f, 1e-2f) : u < 0.2f ? r.log_uniform(1e-6f, 0.2f) : r.uniform(-0.2f, 1.2f);
    const glm::vec3 p(r.uniform(-100, 100), r.uniform(-100, 100), r.uniform(-100, 100));
    cases.push_back({glm::vec4(p, c), glm::vec4(r.unit(), r.log_uniform(1e-4f, 10)), glm::vec4(r.uniform(0, 2), r.uniform(0, 3), r.uniform(0, 3), 0)});
  }
  const std::vector<std::string> kLookup = {"06_shadows/shaders/lookup_math.glsl"};
  const auto gpu_bias = test::run_glsl_twin({kLookup, "slope_scaled_bias(c.x, c.y, a.w, b.w), 0.0, 0.0, 0.0"}, cases);
  const auto gpu_offset = test::run_glsl_twin({kLookup, "normal_offset(a.xyz, b.xyz, a.w, c.z, b.w), 0.0"}, cases);
  std::vector<glm::vec4> cpu_bias, cpu_offset;
  std::vector<double> bias_tolerance, offset_tolerance;
  for (const TwinCase& t : cases) {
    const float w = t.b.w, constant = t.c.x, slope = t.c.y, texels = t.c.z;
    const float bias = slope_scaled_bias(constant, slope, t.a.w, w);
    const glm::vec3 offset = normal_offset(glm::vec3(t.a), glm::vec3(t.b), t.a.w, texels, w);
    cpu_bias.push_back(glm::vec4(bias, 0, 0, 0));
    cpu_offset.push_back(glm::vec4(offset, 0));
    const auto dsin_at = [](double c) {
      const double sin = std::sqrt(std::max(1 - c * c, 0.0));
      return std::min(std::sqrt(2 * kU), sin > 0 ? kU / sin : 1.0) + test::ulps(5) * sin;
    };
    const double cb = std::clamp(double(t.a.w), 1e-4, 1.0), tan = std::sqrt(1 - cb * cb) / cb;
    const double dtan = tan < 10 * (1 + 1e-6) ? dsin_at(cb) / cb + test::ulps(3) * tan : 0.0;  // past the cap both are 10
    bias_tolerance.push_back(6 * kU * w * (constant + slope * std::min(tan, 10.0)) + w * slope * dtan);
    const double co = std::clamp(double(t.a.w), 0.0, 1.0), k = double(texels) * w * std::sqrt(1 - co * co);
    const double dk = double(texels) * w * dsin_at(co) + 2 * kU * k;
    double o = 0;
    for (int i = 0; i < 3; ++i)
      o = std::max(o, std::abs(double(t.b[i])) * dk + 2 * kU * std::abs(t.b[i] * k) + 2 * kU * std::abs(double(offset[i])));
    offset_tolerance.push_back(o);
  }
  const auto describe = [&](std::size_t i) { return describe4(cases, i); };
  EXPECT_TRUE(test::twins_agree(gpu_bias, cpu_bias, 1, [&](std::size_t i) { return test::TwinTolerance{bias_tolerance[i], 0}; }, describe))
      << "slope_scaled_bias";
  EXPECT_TRUE(test::twins_agree(gpu_offset, cpu_offset, 3, [&](std::size_t i) { return test::TwinTolerance{offset_tolerance[i], 0}; }, describe))
      << "normal_offset";
}

// A cube map texel's width (lookup_math.glsl's cube_texel_world against cube_math.h's, which
// point_visibility() scales its biases and normal offset by): 2 d is exact on both sides, the
// division by N is 2.5 ulp in GLSL and half an ulp in C++, so 3 ulp of the result apart. Cases:
// distances 1 mm to 10 km (log-uniform) and 0, faces of 1 to 8192 texels (powers of two and not).
TEST(GlslTwins, CubeTexelWorldMatchesItsCppTwin) {
  test::TwinRandom r(72);
  std::vector<TwinCase> cases;
  for (float d : {0.f, 1.f, 1e-3f, 1e4f, 0.5f})
    for (int n : {1, 2, 3, 16, 100, 512, 1000, 1024, 4096, 8192}) cases.push_back({glm::vec4(d, float(n), 0, 0)});
  while (cases.size() < 12000) {
    const int n = cases.size() % 2 == 0 ? 1 << (int(r.uniform(0, 14)) % 14) : 1 + int(r.uniform(0, 8192));
    cases.push_back({glm::vec4(r.log_uniform(1e-3f, 1e4f), float(n), 0, 0)});
  }
  const auto gpu = test::run_glsl_twin({{"06_shadows/shaders/lookup_math.glsl"}, "cube_texel_world(a.x, a.y), 0.0, 0.0, 0.0"}, cases);
  std::vector<glm::vec4> cpu;
  for (const TwinCase& c : cases) cpu.push_back(glm::vec4(cube_texel_world(c.a.x, int(c.a.y)), 0, 0, 0));
  EXPECT_TRUE(test::twins_agree(gpu, cpu, 1, test::TwinTolerance{0, test::ulps(3)}, [&](std::size_t i) { return describe4(cases, i); }));
}

}  // namespace
}  // namespace lp::ch06
