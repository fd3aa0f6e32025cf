#pragma once
// The lighting model of the whole book, on the CPU. shaders/lighting.glsl is the same maths
// in GLSL; the unit tests hold this file to the formulas and the ground-truth renderer uses
// it, so the GPU images are checked against an independent evaluation.
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "common/scene.h"

namespace lp::ch01 {

// [roughness-to-exponent]
// glTF gives roughness r; Blinn-Phong wants an exponent n. Matching the Blinn-Phong lobe to
// a Beckmann distribution of slope alpha = r^2 gives n = 2 / alpha^2 - 2 (Walter et al. 2007).
inline float exponent_from_roughness(float roughness) {
  float alpha = std::max(roughness * roughness, 1e-3f);
  return std::clamp(2.f / (alpha * alpha) - 2.f, 1.f, 8192.f);
}
// [/roughness-to-exponent]

// [attenuation]
// Inverse-square falloff, faded to exactly zero at `range` with the window glTF recommends
// (KHR_lights_punctual). range = 0 means unbounded. d is kept above 1 cm so a surface
// touching the light does not divide by zero.
inline float distance_attenuation(float distance, float range) {
  float d2 = std::max(distance * distance, 1e-4f);
  float window = 1.f;
  if (range > 0) {
    float ratio = distance / range;
    window = std::clamp(1.f - ratio * ratio * ratio * ratio, 0.f, 1.f);
    window *= window;
  }
  return window / d2;
}

// Smooth fade from the inner to the outer cone: 1 inside the inner cone, 0 outside the outer.
inline float spot_attenuation(float cos_angle, float inner_cone, float outer_cone) {
  float cos_outer = std::cos(outer_cone), cos_inner = std::cos(inner_cone);
  float scale = 1.f / std::max(1e-4f, cos_inner - cos_outer);
  float t = std::clamp((cos_angle - cos_outer) * scale, 0.f, 1.f);
  return t * t;
}
// [/attenuation]

struct SurfacePoint {
  glm::vec3 position, normal;  // normal: unit length, unless the caller wants to show why it must be
  glm::vec3 to_eye;            // unit vector from the surface to the camera
  glm::vec3 albedo, specular;
  float exponent;
};

// What one light sends towards the surface: the direction to it and the irradiance scale.
struct Incident {
  glm::vec3 to_light{0};
  glm::vec3 radiance{0};  // colour x intensity x attenuation
};

inline Incident incident(const Light& light, const glm::vec3& position) {
  Incident in;
  if (light.type == LightType::Directional) {
    in.to_light = -light.direction;
    in.radiance = light.color * light.intensity;
    return in;
  }
  glm::vec3 d = light.position - position;
  float distance = glm::length(d);
  in.to_light = distance > 0 ? d / distance : glm::vec3(0, 1, 0);
  float a = distance_attenuation(distance, light.range);
  if (light.type == LightType::Spot)
    a *= spot_attenuation(glm::dot(-in.to_light, light.direction), light.inner_cone, light.outer_cone);
  in.radiance = light.color * light.intensity * a;
  return in;
}

// [blinn-phong]
// Lambert diffuse plus normalised Blinn-Phong specular for one light, split in two so later
// chapters can accumulate diffuse and specular light separately. Display units: the 1/pi of
// the Lambert BRDF is folded into the light intensity.
struct Reflected {
  glm::vec3 diffuse{0}, specular{0};  // light reflected, before multiplying by the albedo
};

inline Reflected blinn_phong(const glm::vec3& n, const glm::vec3& to_eye, const glm::vec3& to_light,
                             const glm::vec3& radiance, float exponent) {
  float n_dot_l = glm::dot(n, to_light);
  if (n_dot_l <= 0) return {};
  // The eye exactly opposite the light (below the surface, where a silhouette's interpolated
  // normal can put it) has no half vector, and sees no highlight: not normalize(0), a NaN.
  if (to_light + to_eye == glm::vec3(0)) return {radiance * n_dot_l, glm::vec3(0)};
  glm::vec3 h = glm::normalize(to_light + to_eye);
  float n_dot_h = std::max(glm::dot(n, h), 0.f);
  // (n + 8) / 8 keeps the lobe's energy roughly constant as it narrows.
  float lobe = (exponent + 8.f) / 8.f * std::pow(n_dot_h, exponent);
  return {radiance * n_dot_l, radiance * (lobe * n_dot_l)};
}
// [/blinn-phong]

// Everything that reaches the eye from a surface point: all lights, ambient and emissive.
inline glm::vec3 shade(const SurfacePoint& s, const Scene& scene, const glm::vec3& emissive) {
  glm::vec3 diffuse(0), specular(0);
  for (const auto& light : scene.lights) {
    Incident in = incident(light, s.position);
    Reflected r = blinn_phong(s.normal, s.to_eye, in.to_light, in.radiance, s.exponent);
    diffuse += r.diffuse;
    specular += r.specular;
  }
  return s.albedo * (diffuse + scene.ambient) + s.specular * specular + emissive;
}

}  // namespace lp::ch01
