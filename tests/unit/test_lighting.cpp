// The lighting maths of chapter 01 (blinn_phong.h), held to the formulas.
#include <gtest/gtest.h>

#include <cmath>

#include "chapters/01_forward/blinn_phong.h"
#include "chapters/01_forward/light_buffer.h"

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
