// Chapter 07's GLSL functions against their C++ twins (ao_math.h, and chapter 03's
// basis_around), on the GPU (glsl_twin.h): ao_math.glsl, which ssao.comp and blur.comp include.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "chapters/03_light_volumes/light_instances.h"
#include "chapters/07_ssao/ao_math.h"
#include "tests/unit/glsl_twin.h"

namespace lp::ch07 {
namespace {

using test::TwinCase;
using test::ulps;
const std::vector<std::string> kAo = {"07_ssao/shaders/ao_math.glsl"};
constexpr double kPi = 3.14159265358979;
// GLSL 4.50 gives sin and cos no precision; Vulkan's environment allows 2^-11 absolutely on
// [-pi, pi]. We allow 2^-20 absolutely for arguments of a few pi: a bound on the implementation
// (llvmpipe's and NVIDIA's are well within it), not the specification's.
constexpr double kTrig = 0x1p-20;

std::string describe4(const std::vector<TwinCase>& cases, std::size_t i) {
  return test::str(cases[i].a) + " " + test::str(cases[i].b) + " " + test::str(cases[i].c) + " " + test::str(cases[i].d);
}

TEST(GlslTwins, BasisAndNoiseReflectionMatchTheirCppTwins) {
  // basis(n): chapter 03's basis_around's first two columns (the same Duff et al. formula; its
  // tolerance is derived in test_03_twins_gl.cpp: 12 ulp of 1). reflect_about(k, r) for kernel
  // points k (|k| <= 1) and unit r: a 3-term dot, a product and a difference, within 4 ulp of
  // 1 on each side absolutely: 8. Edge cases: the poles, k along r (reflected to -k), k = 0.
  test::TwinRandom r(7);
  std::vector<TwinCase> cases;
  for (glm::vec3 n : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(1, 0, 0)})
    cases.push_back({glm::vec4(n, 0), glm::vec4(n, 0), glm::vec4(n, 0)});
  cases.push_back({glm::vec4(0, 0, 1, 0), glm::vec4(0), glm::vec4(1, 0, 0, 0)});
  while (cases.size() < 10000 + 4) {
    glm::vec3 k = clamp_to_kernel_hemisphere(r.unit() * r.uniform(0, 1));
    glm::vec3 noise = r.uniform(0, 1) < 0.5f ? r.unit() : glm::normalize(glm::vec3(r.uniform(-1, 1), r.uniform(-1, 1), 0.f));
    cases.push_back({glm::vec4(r.unit(), 0), glm::vec4(k, 0), glm::vec4(noise, 0)});
  }
  const std::string helper = "vec4 twin_basis(vec3 n, bool t) { vec3 tt, bb; basis(n, tt, bb); return vec4(t ? tt : bb, 0.0); }";
  const auto t = test::run_glsl_twin({kAo, "twin_basis(a.xyz, true)", {}, helper}, cases);
  const auto b = test::run_glsl_twin({kAo, "twin_basis(a.xyz, false)", {}, helper}, cases);
  const auto reflected = test::run_glsl_twin({kAo, "reflect_about(b.xyz, c.xyz), 0.0"}, cases);
  std::vector<glm::vec4> cpu_t, cpu_b, cpu_reflected;
  for (const auto& c : cases) {
    const glm::mat3 m = ch03::basis_around(glm::vec3(c.a));
    cpu_t.push_back(glm::vec4(m[0], 0));
    cpu_b.push_back(glm::vec4(m[1], 0));
    cpu_reflected.push_back(glm::vec4(reflect_about(glm::vec3(c.b), glm::vec3(c.c)), 0));
  }
  auto describe = [&](std::size_t i) { return describe4(cases, i); };
  EXPECT_TRUE(test::twins_agree(t, cpu_t, 3, {ulps(12), 0}, describe)) << "tangent";
  EXPECT_TRUE(test::twins_agree(b, cpu_b, 3, {ulps(12), 0}, describe)) << "bitangent";
  EXPECT_TRUE(test::twins_agree(reflected, cpu_reflected, 3, {ulps(8), 0}, describe)) << "reflection";
}

TEST(GlslTwins, RangeCheckMatchesItsCppTwin) {
  // smoothstep(0, 1, radius / max(|gap|, 1e-6)) for radii from 1 mm to 10 m and gaps of either
  // sign to 100 m, plus 0 and the edge of the radius. t is a division (GLSL 2.5 ulp, C++ 0.5);
  // the smoothstep's slope is at most 1.5, and its three operations add 2 ulp of 1 on each side:
  // 1.5 x 3 + 4, 9 ulp of 1 absolutely.
  test::TwinRandom r(8);
  std::vector<TwinCase> cases;
  for (float gap : {0.f, -0.f, 1e-7f, 1.f, -1.f, 2.f, 1e6f}) cases.push_back({glm::vec4(1, gap, 0, 0)});
  cases.push_back({glm::vec4(0, 1, 0, 0)});
  while (cases.size() < 10000 + 8) {
    float radius = r.log_uniform(1e-3f, 10);
    float gap = (r.uniform(0, 1) < 0.5f ? -1.f : 1.f) * radius * r.log_uniform(0.1f, 100);
    cases.push_back({glm::vec4(radius, gap, 0, 0)});
  }
  const auto gpu = test::run_glsl_twin({kAo, "range_weight(a.x, a.y)"}, cases);
  std::vector<glm::vec4> cpu;
  for (const auto& c : cases) cpu.push_back(glm::vec4(range_weight(c.a.x, c.a.y)));
  EXPECT_TRUE(test::twins_agree(gpu, cpu, 1, {ulps(9), 0}, [&](std::size_t i) { return "radius, gap " + test::str(cases[i].a); }));
}

TEST(GlslTwins, DiskSpiralMatchesItsCppTwin) {
  // Every point of the spiral for every sample count 1..128 (turn 0: spiral_point's). The
  // radius: a division and a sqrt (GLSL: 1 / inversesqrt), 8 ulp on the GLSL side and 1 on the
  // C++; the angle i x 2.39996323 may differ by 1 ulp of itself; cos and sin: kTrig.
  std::vector<TwinCase> cases;
  for (int n = 1; n <= 144; ++n)
    for (int i = 0; i < n; ++i) cases.push_back({glm::vec4(float(i), float(n), 0, 0)});
  ASSERT_GE(cases.size(), 10000u);
  const std::string helper = "vec2 twin_spiral(int i, int n) { vec2 p = spiral_polar(i, n, 0.0); return p.x * vec2(cos(p.y), sin(p.y)); }";
  const auto gpu = test::run_glsl_twin({kAo, "twin_spiral(int(a.x), int(a.y)), 0.0, 0.0", {}, helper}, cases);
  std::vector<glm::vec4> cpu;
  for (const auto& c : cases) cpu.push_back(glm::vec4(spiral_point(int(c.a.x), int(c.a.y)), 0, 0));
  EXPECT_TRUE(test::twins_agree(
      gpu, cpu, 2, [&](std::size_t i) { return test::TwinTolerance{ulps(9) + ulps(1) * 2.4 * cases[i].a.x + kTrig, 0}; },
      [&](std::size_t i) { return "i, n " + test::str(cases[i].a); }));
}

// Receivers and emitters in a 4 m box, random unit normals, areas from 1 cm^2 to 1 m^2, and the
// edge cases: the same point, no area, an emitter behind the receiver, on its tangent plane,
// close, far.
std::vector<TwinCase> disk_cases(std::uint64_t seed) {
  test::TwinRandom r(seed);
  std::vector<TwinCase> cases;
  const glm::vec4 up(0, 0, 1, 0), p(0, 0, 0, 0.1f);  // a.w: the area
  cases.push_back({p, up, glm::vec4(0), -up});
  cases.push_back({glm::vec4(0), up, glm::vec4(0, 0, 1, 0), -up});
  cases.push_back({p, up, glm::vec4(0, 0, -1, 0), up});
  cases.push_back({p, up, glm::vec4(1, 0, 0, 0), glm::vec4(-1, 0, 0, 0)});
  cases.push_back({p, up, glm::vec4(0, 0, 0.01f, 0), -up});
  cases.push_back({p, up, glm::vec4(0, 0.2f, 0.02f, 0), -up});  // low: inside the receiver's 4x ramp
  cases.push_back({p, up, glm::vec4(0, 0, 1000, 0), up});
  while (cases.size() < 10000 + 7) {
    glm::vec3 a(r.uniform(-2, 2), r.uniform(-2, 2), r.uniform(-2, 2)), e(r.uniform(-2, 2), r.uniform(-2, 2), r.uniform(-2, 2));
    cases.push_back({glm::vec4(a, r.log_uniform(1e-4f, 1)), glm::vec4(r.unit(), 0), glm::vec4(e, 0), glm::vec4(r.unit(), 0)});
  }
  return cases;
}

TEST(GlslTwins, DiskTermsMatchTheirCppTwins) {
  // Both occlusion terms of the 2D disk. v = e - p is the same subtraction on both sides, d^2
  // a dot (1.5 ulp), v / d (GLSL: inversesqrt and a product; C++: sqrt and a division), so
  // each cosine within 6 ulp of 1 absolutely on either side.
  // The form factor A |ne.v| max(np.v, 0) / (pi d^2 + A): 2 x 2 x 6 ulp of A / (pi d^2 + A)
  // absolutely, and the products and division 4.5 ulp (GLSL) + 2 (C++) relative.
  // Bunnell's 1 - 1 / sqrt(1 + A / (pi d^2)): 1 + x rounds by half an ulp of 1, inversesqrt by
  // 2 ulp (GLSL; C++ 1): the solid-angle factor within 5 ulp of 1 absolutely; its cosines,
  // |ne.v| and clamp(4 np.v, 0, 1), are within 2 x 6 and 2 x 24 ulp absolutely, on the factor.
  const auto cases = disk_cases(9);
  const auto ff = test::run_glsl_twin({kAo, "form_factor_occlusion(a.xyz, b.xyz, c.xyz, d.xyz, a.w)"}, cases);
  const auto bunnell = test::run_glsl_twin({kAo, "bunnell_occlusion(a.xyz, b.xyz, c.xyz, d.xyz, a.w)"}, cases);
  std::vector<glm::vec4> cpu_ff, cpu_bunnell;
  for (const auto& c : cases) {
    cpu_ff.push_back(glm::vec4(form_factor_occlusion(glm::vec3(c.a), glm::vec3(c.b), glm::vec3(c.c), glm::vec3(c.d), c.a.w)));
    cpu_bunnell.push_back(glm::vec4(bunnell_occlusion(glm::vec3(c.a), glm::vec3(c.b), glm::vec3(c.c), glm::vec3(c.d), c.a.w)));
  }
  auto d2 = [&](std::size_t i) { return double(glm::dot(glm::vec3(cases[i].c - cases[i].a), glm::vec3(cases[i].c - cases[i].a))); };
  auto describe = [&](std::size_t i) { return describe4(cases, i); };
  EXPECT_TRUE(test::twins_agree(
      ff, cpu_ff, 1,
      [&](std::size_t i) {
        const double area = cases[i].a.w;
        return test::TwinTolerance{area / (kPi * d2(i) + area) * ulps(24), ulps(7)};
      },
      describe))
      << "form factor";
  EXPECT_TRUE(test::twins_agree(
      bunnell, cpu_bunnell, 1,
      [&](std::size_t i) {
        const double solid = d2(i) > 0 ? 1 - 1 / std::sqrt(1 + cases[i].a.w / (kPi * d2(i))) : 0;
        return test::TwinTolerance{ulps(5) + solid * ulps(60), ulps(4)};
      },
      describe))
      << "Bunnell";
}

TEST(GlslTwins, BilateralWeightMatchesItsCppTwin) {
  // A 0/1 test: equal on both sides except where an input lies within rounding of a
  // threshold: |z - zc| within 2 ulp of zc of depth_threshold x zc (a subtraction and a
  // product), or n . nc within 2 x 3 ulp of 1 of normal_threshold (a 3-term dot of unit vectors
  // each side). There either answer is right and the tolerance is 1. Depths are positive (the
  // sky, which the C++ twin also gives 0, is skipped before the GLSL's call). Edge cases: the
  // same depth and normal, and depths and normals at the thresholds exactly.
  test::TwinRandom r(10);
  std::vector<TwinCase> cases;
  const glm::vec4 up(0, 0, 1, 0);
  cases.push_back({glm::vec4(2, 2, 0.05f, 0.8f), up, up});
  cases.push_back({glm::vec4(2, 2.1f, 0.05f, 0.8f), up, up});  // at the depth threshold
  cases.push_back({glm::vec4(2, 2, 0.05f, 0.8f), up, glm::vec4(0.6f, 0, 0.8f, 0)});  // at the normal threshold
  while (cases.size() < 10000 + 3) {
    const float zc = r.log_uniform(0.1f, 100), t = r.uniform(0, 1) < 0.5f ? 0.05f : r.uniform(0.01f, 0.2f);
    const float nt = r.uniform(0, 1) < 0.5f ? 0.8f : r.uniform(-1, 1);
    const glm::vec3 nc = r.unit(), n = glm::normalize(nc + r.uniform(0, 1.5f) * r.unit());
    cases.push_back({glm::vec4(zc, zc * (1 + r.uniform(-2 * t, 2 * t)), t, nt), glm::vec4(nc, 0), glm::vec4(n, 0)});
  }
  const auto gpu = test::run_glsl_twin({kAo, "bilateral_weight(a.x, a.y, b.xyz, c.xyz, a.z, a.w)"}, cases);
  std::vector<glm::vec4> cpu;
  for (const auto& c : cases) cpu.push_back(glm::vec4(bilateral_weight(c.a.x, c.a.y, glm::vec3(c.b), glm::vec3(c.c), c.a.z, c.a.w)));
  EXPECT_TRUE(test::twins_agree(
      gpu, cpu, 1,
      [&](std::size_t i) {
        const auto& a = cases[i].a;
        const double depth_margin = std::abs(std::abs(double(a.y) - a.x) - double(a.z) * a.x);
        const double normal_margin = std::abs(double(glm::dot(glm::vec3(cases[i].b), glm::vec3(cases[i].c))) - a.w);
        const bool at_threshold = depth_margin <= ulps(2) * a.x || normal_margin <= ulps(6);
        return test::TwinTolerance{at_threshold ? 1.0 : 0.0, 0};
      },
      [&](std::size_t i) { return describe4(cases, i); }));
}

TEST(GlslTwins, GtaoHorizonAndArcMatchTheirCppTwins) {
  // gtao_horizon over receivers 0.5 to 20 m in front of the camera, occluders within 1.5 R of
  // them (R from 0.1 to 2 m, u_falloff 0.05, the bias 0.02 R: the chapter's), unit normals and
  // lows in [-1, 0]; plus the receiver itself and an occluder on the bias height.
  // Tolerance: |q - p| is a dot and a sqrt (GLSL 6 ulp, C++ 2); the weight dist x mul + add
  // then moves by 8 ulp of |dist x mul| plus 1 of |add| (mul = -1 / (0.05 R), so both are ~20),
  // and the elevation (delta / dist) . view_vec is within 12 ulp of 1 (GLSL) and 4 (C++); mix
  // moves by |elevation - low| times the weight's error, plus the elevation's, plus 4 ulp. Where
  // delta . normal is within rounding of the bias height (3 ulp of |delta| each side), either
  // side of it is right: the tolerance is |elevation - low|.
  test::TwinRandom r(11);
  std::vector<TwinCase> cases;
  std::vector<float> radius;
  auto add = [&](glm::vec3 p, glm::vec3 q, glm::vec3 n, float low, float R) {
    // a: p, low; b: q, falloff_mul; c: normal, falloff_add; d: view_vec, min_height
    const float range = 0.05f * R, from = R - range;
    cases.push_back({glm::vec4(p, low), glm::vec4(q, -1.f / range), glm::vec4(n, from / range + 1.f),
                     glm::vec4(glm::normalize(-p), 0.02f * R)});
    radius.push_back(R);
  };
  add(glm::vec3(0, 0, -2), glm::vec3(0, 0, -2), glm::vec3(0, 1, 0), -0.5f, 1);                 // the receiver itself
  add(glm::vec3(0, 0, -2), glm::vec3(0, 0.02f, -1.5f), glm::vec3(0, 1, 0), -0.5f, 1);          // on the bias height
  while (cases.size() < 10000 + 2) {
    const float R = r.log_uniform(0.1f, 2);
    const glm::vec3 p = r.unit() * glm::vec3(2, 2, 0) + glm::vec3(0, 0, -r.log_uniform(0.5f, 20));
    glm::vec3 n = r.unit();
    if (glm::dot(n, -p) < 0) n = -n;  // facing the camera
    add(p, p + r.unit() * r.uniform(0, 1.5f * R), n, r.uniform(-1, 0), R);
  }
  const auto gpu = test::run_glsl_twin({kAo, "gtao_horizon(a.xyz, b.xyz, c.xyz, d.xyz, a.w, b.w, c.w, d.w)"}, cases);
  std::vector<glm::vec4> cpu;
  for (const auto& c : cases)
    cpu.push_back(glm::vec4(gtao_horizon(glm::vec3(c.a), glm::vec3(c.b), glm::vec3(c.c), glm::vec3(c.d), c.a.w, c.b.w, c.c.w, c.d.w)));
  EXPECT_TRUE(test::twins_agree(
      gpu, cpu, 1,
      [&](std::size_t i) {
        const auto& c = cases[i];
        const glm::vec3 delta = glm::vec3(c.b) - glm::vec3(c.a);
        const double dist = glm::length(delta);
        if (!(dist > 0)) return test::TwinTolerance{0, 0};
        const double elevation = glm::dot(delta / float(dist), glm::vec3(c.d));
        const double swing = std::abs(elevation - c.a.w);
        if (std::abs(double(glm::dot(delta, glm::vec3(c.c))) - c.d.w) <= ulps(6) * dist) return test::TwinTolerance{swing, 0};
        const double weight_error = ulps(8) * std::abs(dist * c.b.w) + ulps(1) * std::abs(double(c.c.w));
        return test::TwinTolerance{swing * weight_error + ulps(16) + ulps(4), 0};
      },
      [&](std::size_t i) { return describe4(cases, i); }))
      << "horizon";

  // gtao_arc(h, n, cos n) for projected normals within the hemisphere (n in [-pi/2, pi/2]) and
  // horizons within pi/2 of them, plus the tangent plane's two sides and the view vector.
  // (cos n + 2 h sin n - cos(2h - n)) / 4: sin n and cos(2h - n) within kTrig, the first
  // times |2h| <= 2 pi; 2h - n within 2 ulp of 2 pi; the sums 4 ulp of 2 (the largest term) on
  // each side; over 4.
  std::vector<TwinCase> arcs;
  for (float n : {-1.5707963f, -0.5f, 0.f, 0.5f, 1.5707963f})
    for (float h : {n - 1.5707963f, 0.f, n, n + 1.5707963f}) arcs.push_back({glm::vec4(h, n, std::cos(n), 0)});
  while (arcs.size() < 10000 + 20) {
    const float n = r.uniform(-1.5707963f, 1.5707963f), h = n + r.uniform(-1.5707963f, 1.5707963f);
    arcs.push_back({glm::vec4(h, n, std::cos(n), 0)});
  }
  const auto gpu_arcs = test::run_glsl_twin({kAo, "gtao_arc(a.x, a.y, a.z)"}, arcs);
  std::vector<glm::vec4> cpu_arcs;
  for (const auto& c : arcs) cpu_arcs.push_back(glm::vec4(gtao_arc(c.a.x, c.a.y, c.a.z)));
  EXPECT_TRUE(test::twins_agree(
      gpu_arcs, cpu_arcs, 1,
      [&](std::size_t i) {
        const double h = std::abs(arcs[i].a.x);
        return test::TwinTolerance{(kTrig * (2 * h + 1) + 2 * ulps(2) * 2 * kPi + 2 * ulps(4) * 2) / 4, 0};
      },
      [&](std::size_t i) { return "h, n, cos n " + test::str(arcs[i].a); }))
      << "arc";
}

}  // namespace
}  // namespace lp::ch07
