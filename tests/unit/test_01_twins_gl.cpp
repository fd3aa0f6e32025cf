// Chapter 01's GLSL functions against their C++ twins (blinn_phong.h), on the GPU
// (glsl_twin.h): lighting.glsl's distance_attenuation(), light_incident() and blinn_phong().
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "chapters/01_forward/blinn_phong.h"
#include "chapters/01_forward/light_buffer.h"
#include "tests/unit/glsl_twin.h"
#include "tests/unit/lighting_cases.h"

namespace lp::ch01 {
namespace {

using test::TwinCase;
using test::ulps;
constexpr float kInf = std::numeric_limits<float>::infinity();
const std::vector<std::string> kLighting = {"01_forward/shaders/lighting.glsl"};

TEST(GlslTwins, DistanceAttenuationMatchesItsCppTwin) {
  // Distances from 0 to 3 ranges (log-uniform from 1 mm: the falloff spans decades) with
  // unbounded lights among them, and 0, the 1 cm floor, the range itself, huge and infinite.
  // Not NaN: GLSL's max(NaN, 1e-4) may give either operand (llvmpipe gives 1e-4, C++ NaN), and
  // a distance between finite positions is never NaN.
  // Tolerance: ratio = d / range (GLSL: 2.5 ulp), ratio^4 (3 products: 4 x 2.5 + 1.5 = 11.5 ulp
  // of a value <= 1, where it matters), 1 - ratio^4 (+0.5), squared (x 2): the window within
  // 24 ulp of 1, absolutely; the C++ side's 8. Divided by d^2 (>= 1e-4; GLSL: 2.5 + 0.5 ulp,
  // C++ 1): 32 ulp / max(d^2, 1e-4) absolute plus 8 ulp relative.
  test::TwinRandom r(1);
  std::vector<TwinCase> cases;
  for (float range : {0.f, 1.f, 4.f})
    for (float d : {0.f, 1e-3f, 0.01f, 0.5f, 1.f, 4.f, 1e20f, kInf}) cases.push_back({glm::vec4(d, range, 0, 0)});
  while (cases.size() < 10000 + 24) {
    float range = r.uniform(0, 1) < 0.2f ? 0.f : r.log_uniform(0.1f, 100.f);
    float d = r.uniform(0, 1) < 0.5f ? r.log_uniform(1e-3f, 300.f) : r.uniform(0, 3 * std::max(range, 1.f));
    cases.push_back({glm::vec4(d, range, 0, 0)});
  }
  const auto gpu = test::run_glsl_twin({kLighting, "distance_attenuation(a.x, a.y)"}, cases);
  std::vector<glm::vec4> cpu;
  for (const auto& c : cases) cpu.push_back(glm::vec4(distance_attenuation(c.a.x, c.a.y)));
  EXPECT_TRUE(test::twins_agree(
      gpu, cpu, 1,
      [&](std::size_t i) {
        const double d2 = std::max(double(cases[i].a.x) * cases[i].a.x, 1e-4);
        return test::TwinTolerance{ulps(32) / d2, ulps(8)};
      },
      [&](std::size_t i) { return "distance, range = " + test::str(cases[i].a); }));
}

// A light and a surface point as four vec4: chapter 01's GpuLight (pack_light) with the
// point in its unused components (radiance.w, spot.zw).
TwinCase light_case(const Light& light, glm::vec3 p) {
  GpuLight g = pack_light(light);
  return {g.position_type, g.direction_range, glm::vec4(glm::vec3(g.radiance), p.x), glm::vec4(g.spot.x, g.spot.y, p.y, p.z)};
}
const std::string kIncidentHelper =
    "vec4 twin_incident(vec4 a, vec4 b, vec4 c, vec4 d, bool dir) { vec3 t, r; "
    "light_incident(GpuLight(a, b, vec4(c.xyz, 0.0), vec4(d.xy, 0.0, 0.0)), vec3(c.w, d.zw), t, r); "
    "return vec4(dir ? t : r, 0.0); }";

TEST(GlslTwins, LightIncidentMatchesItsCppTwin) {
  // Directional, point and spot lights at random places, ranges, cones and colours, surface
  // points within 10 m, plus a point on the light, at its range and on the cone's edges.
  // Tolerance: d is the same subtraction on both sides; |d| is a dot (1.5 ulp) and a sqrt
  // (GLSL: 1 / inversesqrt, 4.5 ulp), to_light = d / |d| (+2.5): 10 ulp of the unit vector
  // with the C++ side's 3, absolutely. The radiance: the attenuation's tolerance above with
  // |d|'s 6 ulp carried through ratio^4 (x 4, squared: 48 ulp of the window absolutely) and
  // the spot's t = (cos - cos_outer) x scale: 13 ulp of the cosine times the scale, squared
  // (x 2): 26 ulp x scale absolutely, on the light's radiance / max(d^2, 1e-4).
  test::TwinRandom r(2);
  std::vector<TwinCase> cases;
  std::vector<Light> lights;
  std::vector<glm::vec3> points;
  auto add = [&](const Light& l, glm::vec3 p) {
    lights.push_back(l);
    points.push_back(p);
    cases.push_back(light_case(l, p));
  };
  Light spot{.type = LightType::Spot, .intensity = 2.f, .position = {0, 2, 0}, .direction = {0, -1, 0}, .range = 5.f,
             .inner_cone = 0.3f, .outer_cone = 0.5f};
  add(spot, spot.position);                                           // on the light
  add(spot, spot.position + glm::vec3(0, -5, 0));                     // at its range
  add(spot, spot.position + 2.f * glm::vec3(std::sin(0.5f), -std::cos(0.5f), 0));  // on the outer cone
  add(spot, spot.position + 2.f * glm::vec3(std::sin(0.3f), -std::cos(0.3f), 0));  // on the inner cone
  Light point{.type = LightType::Point, .intensity = 1.f, .position = {1, 1, 1}};
  add(point, glm::vec3(1, 1, 1));
  add(point, glm::vec3(1e6f, 0, 0));
  while (cases.size() < 10000 + 6) {
    Light l;
    float kind = r.uniform(0, 3);
    l.type = kind < 1 ? LightType::Directional : kind < 2 ? LightType::Point : LightType::Spot;
    l.color = glm::vec3(r.uniform(0, 1), r.uniform(0, 1), r.uniform(0, 1));
    l.intensity = r.log_uniform(0.01f, 100.f);
    l.position = glm::vec3(r.uniform(-5, 5), r.uniform(-5, 5), r.uniform(-5, 5));
    l.direction = r.unit();
    l.range = r.uniform(0, 1) < 0.3f ? 0.f : r.log_uniform(0.5f, 20.f);
    l.outer_cone = r.uniform(0.05f, 1.5f);
    l.inner_cone = l.outer_cone * r.uniform(0, 1);
    add(l, glm::vec3(r.uniform(-5, 5), r.uniform(-5, 5), r.uniform(-5, 5)));
  }
  const auto to_light = test::run_glsl_twin({kLighting, "twin_incident(a, b, c, d, true)", {}, kIncidentHelper}, cases);
  const auto radiance = test::run_glsl_twin({kLighting, "twin_incident(a, b, c, d, false)", {}, kIncidentHelper}, cases);
  std::vector<glm::vec4> cpu_to_light, cpu_radiance;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    Incident in = incident(lights[i], points[i]);
    cpu_to_light.push_back(glm::vec4(in.to_light, 0));
    cpu_radiance.push_back(glm::vec4(in.radiance, 0));
  }
  auto describe = [&](std::size_t i) {
    return "light " + test::str(cases[i].a) + " " + test::str(cases[i].b) + " " + test::str(cases[i].c) + " " +
           test::str(cases[i].d);
  };
  EXPECT_TRUE(test::twins_agree(to_light, cpu_to_light, 3, {ulps(13), 0}, describe));
  EXPECT_TRUE(test::twins_agree(
      radiance, cpu_radiance, 3,
      [&](std::size_t i) {
        const Light& l = lights[i];
        const double d = glm::distance(l.position, points[i]);
        const double peak = std::max({l.color.r, l.color.g, l.color.b}) * double(l.intensity);
        const double scale = l.type == LightType::Spot ? double(cases[i].d.y) : 0;
        const double window = l.type == LightType::Directional ? 0 : ulps(48 + 26 * scale);
        return test::TwinTolerance{peak * window / std::max(d * d, 1e-4), ulps(16)};
      },
      describe));
}

const std::string kBlinnPhongHelper =
    "vec4 twin_blinn_phong(vec4 a, vec4 b, vec4 c, vec4 d, bool diffuse) { vec3 df = vec3(0.0), sp = vec3(0.0); "
    "blinn_phong(a.xyz, b.xyz, c.xyz, d.xyz, a.w, df, sp); return vec4(diffuse ? df : sp, 0.0); }";

TEST(GlslTwins, BlinnPhongMatchesItsCppTwin) {
  // Random unit normals, eye and light directions, radiances to 10 and exponents 1 to 8192
  // (log-uniform: exponent_from_roughness's range), plus chapter 01's hard cases within that
  // range (lighting_cases.h; LightingGlsl.HardCasesMatchTheCppTwin holds the rest) and NaN normals.
  // Tolerance: n . l is a 3-term dot of unit vectors (GLSL may fuse it): 3 ulp of 1 on each
  // side, so the diffuse within 6 ulp of the radiance absolutely, 2 relatively. The specular:
  // h = normalize(l + e) and n . h within 12 ulp of 1 on each side, which pow(n . h, e) turns
  // into e x 24 ulp / (n . h) relative; GLSL's pow is exp2(e log2 x), whose log2 may be off by
  // 2^-21 absolutely on [0.5, 2] (3 ulp elsewhere): e x 2^-21 x ln 2 relative, and exp2's
  // 3 + 2|e log2 x| ulp. Capped at 1 % of the value, plus n . l's absolute error on the lobe,
  // and a lobe below the smallest normal float (2^-126) that GLSL may flush to 0.
  test::TwinRandom r(3);
  std::vector<TwinCase> cases;
  for (const auto& c : test::lighting_hard_cases()) {
    if (c.exponent > 8192) continue;
    Incident in = incident(c.light, c.position);
    cases.push_back({glm::vec4(c.normal, c.exponent), glm::vec4(c.to_eye, 0), glm::vec4(in.to_light, 0), glm::vec4(in.radiance, 0)});
  }
  const glm::vec3 up(0, 0, 1);
  cases.push_back({glm::vec4(up, 1), glm::vec4(up, 0), glm::vec4(1, 0, 0, 0), glm::vec4(1)});            // n . l = 0
  cases.push_back({glm::vec4(up, 8192), glm::vec4(0, 0, -1, 0), glm::vec4(up, 0), glm::vec4(1)});        // no half vector
  cases.push_back({glm::vec4(up, 8192), glm::vec4(up, 0), glm::vec4(up, 0), glm::vec4(1)});              // the peak
  cases.push_back({glm::vec4(std::nanf(""), 0, 1, 16), glm::vec4(up, 0), glm::vec4(up, 0), glm::vec4(1)});  // NaN normal
  while (cases.size() < 10000 + 24) {
    glm::vec3 n = r.unit(), e = r.unit(), l = r.unit();
    if (glm::dot(n, l) < 0) l = -l;  // most cases lit
    cases.push_back({glm::vec4(n, r.log_uniform(1, 8192)), glm::vec4(e, 0), glm::vec4(l, 0),
                     glm::vec4(r.uniform(0, 10), r.uniform(0, 10), r.uniform(0, 10), 0)});
  }
  const auto diffuse = test::run_glsl_twin({kLighting, "twin_blinn_phong(a, b, c, d, true)", {}, kBlinnPhongHelper}, cases);
  const auto specular = test::run_glsl_twin({kLighting, "twin_blinn_phong(a, b, c, d, false)", {}, kBlinnPhongHelper}, cases);
  std::vector<glm::vec4> cpu_diffuse, cpu_specular;
  for (const auto& c : cases) {
    Reflected out = blinn_phong(glm::vec3(c.a), glm::vec3(c.b), glm::vec3(c.c), glm::vec3(c.d), c.a.w);
    cpu_diffuse.push_back(glm::vec4(out.diffuse, 0));
    cpu_specular.push_back(glm::vec4(out.specular, 0));
  }
  auto describe = [&](std::size_t i) {
    return "n, exponent " + test::str(cases[i].a) + " to_eye " + test::str(cases[i].b) + " to_light " +
           test::str(cases[i].c) + " radiance " + test::str(cases[i].d);
  };
  auto peak = [&](std::size_t i) { return double(std::max({cases[i].d.x, cases[i].d.y, cases[i].d.z})); };
  EXPECT_TRUE(test::twins_agree(diffuse, cpu_diffuse, 3, [&](std::size_t i) { return test::TwinTolerance{peak(i) * ulps(6), ulps(2)}; },
                                describe));
  EXPECT_TRUE(test::twins_agree(
      specular, cpu_specular, 3,
      [&](std::size_t i) {
        const auto& c = cases[i];
        const double e = c.a.w;
        const glm::vec3 sum = glm::vec3(c.c) + glm::vec3(c.b);
        const double n_dot_h = glm::dot(sum, sum) > 0 ? std::max(double(glm::dot(glm::vec3(c.a), glm::normalize(sum))), 1e-6) : 1;
        const double pow_error = e * ulps(24) / n_dot_h + e * 0x1p-21 * std::log(2.0) +
                                 ulps(3 + 2 * std::abs(e * std::log2(n_dot_h))) + ulps(8);
        const double lobe = (e + 8) / 8 * std::pow(n_dot_h, e);
        return test::TwinTolerance{peak(i) * (lobe * ulps(6) + (e + 8) / 8 * 0x1p-126), std::min(pow_error, 0.01)};
      },
      describe));
}

}  // namespace
}  // namespace lp::ch01
