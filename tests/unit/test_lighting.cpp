// The lighting maths of chapter 01 (blinn_phong.h), held to the formulas.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "chapters/01_forward/blinn_phong.h"
#include "chapters/01_forward/light_buffer.h"
#include "tests/unit/lighting_cases.h"

using namespace lp;
using namespace lp::ch01;

TEST(Lighting, ExponentFromRoughnessFollowsBeckmannMatch) {
  EXPECT_NEAR(exponent_from_roughness(0.5f), 30.f, 1e-3f);  // alpha = 0.25: 2/0.0625 - 2
  EXPECT_FLOAT_EQ(exponent_from_roughness(1.f), 1.f);       // 2/1 - 2 = 0, clamped to 1
  float previous = 1e9f;
  for (float r = 0.05f; r <= 1.f; r += 0.05f) {
    float n = exponent_from_roughness(r);
    EXPECT_LE(n, previous) << "smoother surfaces must have sharper highlights (r = " << r << ")";
    EXPECT_TRUE(std::isfinite(n));
    previous = n;
  }
  EXPECT_LE(exponent_from_roughness(0.f), 8192.f);  // a mirror stays finite
}

TEST(Lighting, InverseSquareFalloff) {
  EXPECT_FLOAT_EQ(distance_attenuation(1.f, 0.f), 1.f);
  EXPECT_FLOAT_EQ(distance_attenuation(2.f, 0.f), 0.25f);
  EXPECT_NEAR(distance_attenuation(10.f, 0.f) / distance_attenuation(5.f, 0.f), 0.25f, 1e-6f);
  EXPECT_TRUE(std::isfinite(distance_attenuation(0.f, 0.f)));  // a surface touching the light
  EXPECT_FLOAT_EQ(distance_attenuation(0.f, 0.f), 1e4f);
}

TEST(Lighting, RangeWindowEndsTheLightSmoothly) {
  EXPECT_FLOAT_EQ(distance_attenuation(4.f, 4.f), 0.f);
  EXPECT_FLOAT_EQ(distance_attenuation(5.f, 4.f), 0.f);
  // Close to the light the window hardly changes the inverse square.
  EXPECT_NEAR(distance_attenuation(0.4f, 4.f) / distance_attenuation(0.4f, 0.f), 1.f, 1e-3f);
  float previous = distance_attenuation(0.1f, 4.f);
  for (float d = 0.2f; d < 4.f; d += 0.1f) {
    float a = distance_attenuation(d, 4.f);
    EXPECT_LT(a, previous);
    previous = a;
  }
}

TEST(Lighting, SpotConeIsOneInsideZeroOutsideAndMonotonic) {
  float inner = 0.3f, outer = 0.5f;
  EXPECT_FLOAT_EQ(spot_attenuation(std::cos(0.f), inner, outer), 1.f);
  EXPECT_FLOAT_EQ(spot_attenuation(std::cos(0.29f), inner, outer), 1.f);
  EXPECT_FLOAT_EQ(spot_attenuation(std::cos(0.5f), inner, outer), 0.f);
  EXPECT_FLOAT_EQ(spot_attenuation(std::cos(1.2f), inner, outer), 0.f);
  float previous = 1.f;
  for (float a = 0.3f; a <= 0.5f; a += 0.01f) {
    float s = spot_attenuation(std::cos(a), inner, outer);
    EXPECT_LE(s, previous);
    previous = s;
  }
  EXPECT_TRUE(std::isfinite(spot_attenuation(1.f, 0.5f, 0.5f)));  // inner == outer
}

TEST(Lighting, LambertFollowsTheCosineLaw) {
  glm::vec3 n(0, 0, 1), eye(0, 0, 1), radiance(2.f);
  for (float theta = 0; theta < 1.5f; theta += 0.1f) {
    glm::vec3 l(std::sin(theta), 0, std::cos(theta));
    EXPECT_NEAR(blinn_phong(n, eye, l, radiance, 20.f).diffuse.x, 2.f * std::cos(theta), 1e-5f);
  }
}

TEST(Lighting, NothingFromBehindTheSurface) {
  Reflected r = blinn_phong({0, 0, 1}, {0, 0, 1}, glm::normalize(glm::vec3(0.3f, 0, -1)), glm::vec3(1), 10.f);
  EXPECT_EQ(r.diffuse, glm::vec3(0));
  EXPECT_EQ(r.specular, glm::vec3(0));
}

TEST(Lighting, BlinnPhongPeakAndHalfVector) {
  // Light and eye along the normal: H = N, so the lobe is at its peak (n + 8) / 8.
  Reflected r = blinn_phong({0, 0, 1}, {0, 0, 1}, {0, 0, 1}, glm::vec3(1), 24.f);
  EXPECT_NEAR(r.specular.x, 4.f, 1e-5f);
  // Mirror configuration off the normal: H is still N, only N.L scales it.
  glm::vec3 l = glm::normalize(glm::vec3(1, 0, 1)), e = glm::normalize(glm::vec3(-1, 0, 1));
  EXPECT_NEAR(blinn_phong({0, 0, 1}, e, l, glm::vec3(1), 24.f).specular.x, 4.f * l.z, 1e-5f);
  // Away from the mirror direction the highlight falls as cos(N,H)^n.
  glm::vec3 e2 = glm::normalize(glm::vec3(0, 0.2f, 1));
  glm::vec3 h = glm::normalize(glm::vec3(0, 0, 1) + e2);
  EXPECT_NEAR(blinn_phong({0, 0, 1}, e2, {0, 0, 1}, glm::vec3(1), 24.f).specular.x, 4.f * std::pow(h.z, 24.f), 1e-5f);
}

TEST(Lighting, InterpolatedNormalsAreShorterSoMustBeRenormalised) {
  // The midpoint of two unit normals 90 degrees apart has length cos(45 degrees).
  glm::vec3 a(1, 0, 0), b(0, 1, 0);
  glm::vec3 mid = 0.5f * a + 0.5f * b;
  EXPECT_NEAR(glm::length(mid), std::cos(0.785398f), 1e-6f);
  // Lit head-on along the true normal, the unnormalised one loses 29 % of the diffuse light
  // and, raised to the exponent, nearly all of the highlight.
  glm::vec3 l = glm::normalize(mid);
  Reflected wrong = blinn_phong(mid, l, l, glm::vec3(1), 50.f);
  Reflected right = blinn_phong(glm::normalize(mid), l, l, glm::vec3(1), 50.f);
  EXPECT_NEAR(wrong.diffuse.x / right.diffuse.x, 0.7071f, 1e-3f);
  EXPECT_LT(wrong.specular.x / right.specular.x, 1e-6f);
}

TEST(Lighting, DirectionalLightComesFromMinusItsDirection) {
  Light sun{.type = LightType::Directional, .color = glm::vec3(1, 0.5f, 0.25f), .intensity = 2.f, .direction = {0, -1, 0}};
  Incident in = incident(sun, glm::vec3(100, 3, -7));
  EXPECT_EQ(in.to_light, glm::vec3(0, 1, 0));
  EXPECT_EQ(in.radiance, glm::vec3(2, 1, 0.5f));
}

TEST(Lighting, PackedLightMatchesTheShaderLayout) {
  Light spot{.type = LightType::Spot, .color = glm::vec3(1, 1, 0.5f), .intensity = 4.f, .position = {1, 2, 3},
             .direction = {0, -1, 0}, .range = 7.f, .inner_cone = 0.2f, .outer_cone = 0.4f};
  GpuLight g = pack_light(spot);
  EXPECT_EQ(g.position_type, glm::vec4(1, 2, 3, 2));
  EXPECT_EQ(g.direction_range, glm::vec4(0, -1, 0, 7));
  EXPECT_EQ(glm::vec3(g.radiance), glm::vec3(4, 4, 2));
  EXPECT_FLOAT_EQ(g.spot.x, std::cos(0.4f));
  EXPECT_NEAR(g.spot.y, 1.f / (std::cos(0.2f) - std::cos(0.4f)), 1e-3f);
}

TEST(Lighting, ExtraLightsAreDeterministic) {
  Scene s;
  s.bounds_min = glm::vec3(-5, 0, -5);
  s.bounds_max = glm::vec3(5, 2, 5);
  s.lights.push_back(Light{.name = "own"});
  auto a = lights_for_count(s, 100), b = lights_for_count(s, 100);
  ASSERT_EQ(a.size(), 100u);
  EXPECT_EQ(a.front().name, "own");
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].position, b[i].position);
  for (const auto& l : a) {
    EXPECT_GE(l.position.x, -5.f);
    EXPECT_LE(l.position.x, 5.f);
  }
  EXPECT_EQ(lights_for_count(s, 0).size(), 1u);  // 0: the scene's own lights
}

// --- Hard cases (tests/unit/lighting_cases.h; the GLSL twin is held to the same ones in
// test_forward_gl.cpp) ------------------------------------------------------------------------

namespace {

Reflected evaluate(const lp::test::LightingCase& c) {
  Incident in = incident(c.light, c.position);
  return blinn_phong(c.normal, c.to_eye, in.to_light, in.radiance, c.exponent);
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

const lp::test::LightingCase& hard_case(const std::string& name) {
  static const auto cases = lp::test::lighting_hard_cases();
  for (const auto& c : cases)
    if (c.name == name) return c;
  throw std::runtime_error("no hard case '" + name + "'");
}

}  // namespace

TEST(LightingHardCases, NoLightReachesTheEyeFromBehindTheSurfaceOrFromADegenerateNormal) {
  // Exactly zero, both terms: not small, not NaN (a NaN compares unequal to 0 and fails).
  for (const auto& c : lp::test::lighting_hard_cases()) {
    if (!c.dark) continue;
    Reflected r = evaluate(c);
    EXPECT_EQ(r.diffuse, glm::vec3(0)) << c.name;
    EXPECT_EQ(r.specular, glm::vec3(0)) << c.name;
  }
  // The first case is what makes the specular test necessary: its half vector is above the
  // surface, so the lobe alone would light it.
  const auto& below = hard_case("light below the horizon, half vector above it");
  Incident in = incident(below.light, below.position);
  EXPECT_LT(glm::dot(below.normal, in.to_light), 0.f);
  EXPECT_GT(glm::dot(below.normal, glm::normalize(in.to_light + below.to_eye)), 0.9f);
}

TEST(LightingHardCases, ALampAtTheShadedPointIsFiniteAndHeldAtOneCentimetre) {
  const auto& c = hard_case("lamp at the shaded point");
  Reflected r = evaluate(c);
  // to_light = +y by convention (here the normal, n . l = 1), 1 / max(d^2, 10^-4) = 10^4:
  // diffuse 3 x 10^4 exactly, specular at the lobe's peak (30 + 8) / 8.
  EXPECT_EQ(r.diffuse, glm::vec3(3e4f));
  EXPECT_FLOAT_EQ(r.specular.x, 3e4f * 38.f / 8.f);
}

TEST(LightingHardCases, SharpExponentsPeakAtTheirNormalisationAndStayFinite) {
  // At h = n the lobe is (n + 8) / 8 exactly (pow(1, n) = 1 for every n), however large n is:
  // 1025 at the model's largest exponent 2^13, 125001 at 10^6. (The sun's radiance is 2.)
  EXPECT_EQ(evaluate(hard_case("exponent 2^13, h = n")).specular, glm::vec3(2.f * 1025.f));
  EXPECT_EQ(evaluate(hard_case("exponent 10^6, h = n")).specular, glm::vec3(2.f * 125001.f));
  // Just off the peak: pow's value for the n . h the code computes (float: near 1 it moves in
  // steps of 6e-8, which raised to 10^6 is 6 %), to float precision, strictly below the peak.
  for (const char* name : {"exponent 2^13, h 0.5 degrees off n", "exponent 10^6, h 0.1 degrees off n",
                           "exponent 10^30, h 2 degrees off n (pow underflows)"}) {
    const auto& c = hard_case(name);
    Reflected r = evaluate(c);
    Incident in = incident(c.light, c.position);
    const float n_dot_h = glm::dot(c.normal, glm::normalize(in.to_light + c.to_eye));
    const double n_dot_l = glm::dot(c.normal, in.to_light);
    const double expected = 2.0 * (double(c.exponent) + 8) / 8 * std::pow(double(n_dot_h), double(c.exponent)) * n_dot_l;
    ASSERT_TRUE(finite(r.specular)) << name;
    EXPECT_NEAR(r.specular.x, expected, 1e-5 * expected + 1e-30) << name;
    EXPECT_LT(r.specular.x, 2.0 * (double(c.exponent) + 8) / 8) << name;
  }
  // The three: the lobe at 0.5 degrees keeps 73 % of its peak at 2^13; 0.1 degrees takes
  // 10^6 down to about a fifth; 2 degrees takes 10^30 to exactly 0, not NaN (inf x 0).
  const float peak13 = 2.f * 1025.f, peak6 = 2.f * 125001.f;
  EXPECT_NEAR(evaluate(hard_case("exponent 2^13, h 0.5 degrees off n")).specular.x / peak13, 0.73, 0.01);
  EXPECT_NEAR(evaluate(hard_case("exponent 10^6, h 0.1 degrees off n")).specular.x / peak6, 0.22, 0.03);
  EXPECT_EQ(evaluate(hard_case("exponent 10^30, h 2 degrees off n (pow underflows)")).specular, glm::vec3(0));
}

TEST(LightingHardCases, TheEyeOppositeTheLightHasNoHighlightNotNaN) {
  // l + v = 0: the half vector has no direction. The eye is below the surface (n . v =
  // -n . l < 0), so nothing is reflected towards it; the diffuse is the light's, n . l x 2.
  const auto& c = hard_case("eye exactly opposite the light");
  Reflected r = evaluate(c);
  Incident in = incident(c.light, c.position);
  ASSERT_EQ(in.to_light + c.to_eye, glm::vec3(0));
  EXPECT_EQ(r.specular, glm::vec3(0));
  EXPECT_FLOAT_EQ(r.diffuse.x, 2.f * glm::dot(c.normal, in.to_light));
}

TEST(LightingHardCases, ShadeIsFiniteEverywhere) {
  // Through shade() (what the ground truth calls), every case: finite, ambient and emissive
  // added on top.
  for (const auto& c : lp::test::lighting_hard_cases()) {
    Scene s;
    s.lights = {c.light};
    s.ambient = glm::vec3(0.01f);
    glm::vec3 out = shade({c.position, c.normal, c.to_eye, glm::vec3(0.5f), glm::vec3(0.04f), c.exponent}, s, glm::vec3(0.1f));
    EXPECT_TRUE(finite(out)) << c.name;
    if (c.dark) {
      EXPECT_EQ(out, glm::vec3(0.5f * 0.01f + 0.1f)) << c.name;
    }
  }
}
