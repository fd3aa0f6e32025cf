#include "chapters/08_ssgi/gi_math.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "chapters/01_forward/blinn_phong.h"
#include "chapters/07_ssao/ao_math.h"

namespace lp::ch08 {

namespace {
constexpr float kPi = 3.14159265358979f;
constexpr float kGoldenAngle = 2.39996323f;  // chapter 07's spiral

std::uint32_t wang_hash(std::uint32_t h) {
  h = (h ^ 61u) ^ (h >> 16);
  h *= 9u;
  h ^= h >> 4;
  h *= 0x27d4eb2du;
  h ^= h >> 15;
  return h;
}
}  // namespace

// [transfer-code]
float disk_transfer(glm::vec3 receiver, glm::vec3 receiver_normal, glm::vec3 emitter, glm::vec3 emitter_normal,
                    float emitter_area) {
  glm::vec3 v = emitter - receiver;
  float r2 = glm::dot(v, v);
  if (!(emitter_area > 0.f)) return 0.f;
  if (r2 <= 0.f) return 0.f;  // the same point: no direction, no transfer
  v /= std::sqrt(r2);
  float cos_p = std::max(glm::dot(receiver_normal, v), 0.f);  // the emitter above the receiver's plane
  float cos_o = std::max(-glm::dot(emitter_normal, v), 0.f);  // the emitter's lit side toward the receiver
  return emitter_area * cos_o * cos_p / (kPi * r2 + emitter_area);
}
// [/transfer-code]

int regular_rings(int n) {
  int r = std::max(1, int(std::sqrt(float(std::max(n, 1)))));
  while ((r + 1) * (r + 1) <= n) ++r;
  while (r * r > n && r > 1) --r;
  return r;
}

glm::vec2 pixel_jitter(glm::uvec2 pixel) {
  std::uint32_t a = wang_hash(pixel.x * 1973u + pixel.y * 9277u + 26699u);
  std::uint32_t b = wang_hash(a);
  return glm::vec2(float(a >> 8) / 16777216.f, float(b >> 8) / 16777216.f);
}

glm::vec2 pattern_point(Pattern pattern, int i, int n, glm::uvec2 pixel) {
  if (pattern == Pattern::Regular) {
    int rings = regular_rings(n), spokes = std::max(1, n / rings);
    int ring = i / spokes, spoke = i % spokes;
    float r = std::sqrt((float(ring) + 0.5f) / float(rings));
    float a = 2.f * kPi * float(spoke) / float(spokes);
    return r * glm::vec2(std::cos(a), std::sin(a));
  }
  if (pattern == Pattern::Spiral) return ch07::spiral_point(i, n);
  glm::vec2 j = pixel_jitter(pixel);
  float r = std::sqrt((float(i) + j.y) / float(n));
  float a = kGoldenAngle * float(i) + 2.f * kPi * j.x;
  return r * glm::vec2(std::cos(a), std::sin(a));
}

DirectLightSet direct_lights(const ch03::LightSet& set) {
  DirectLightSet d;
  const float inf = std::numeric_limits<float>::infinity();
  for (const auto& l : set.directional) {
    d.lights.push_back(l);
    d.cut.push_back(inf);
  }
  for (const auto& p : set.points) {
    d.lights.push_back(ch03::unpack(p));
    d.cut.push_back(p.position_radius.w);
  }
  for (const auto* list : {&set.cones, &set.wide_spots})
    for (const auto& s : *list) {
      d.lights.push_back(ch03::unpack(s));
      d.cut.push_back(s.position_radius.w);
    }
  return d;
}

void incident(const ch01::GpuLight& light, glm::vec3 position, glm::vec3& to_light, glm::vec3& radiance,
              float& distance) {
  if (light.position_type.w == 0.f) {  // LIGHT_DIRECTIONAL
    to_light = -glm::vec3(light.direction_range);
    radiance = glm::vec3(light.radiance);
    distance = std::numeric_limits<float>::infinity();
    return;
  }
  glm::vec3 d = glm::vec3(light.position_type) - position;
  distance = glm::length(d);
  to_light = distance > 0.f ? d / distance : glm::vec3(0, 1, 0);
  float a = ch01::distance_attenuation(distance, light.direction_range.w);
  if (light.position_type.w == 2.f) {  // LIGHT_SPOT: spot.x = cos outer, spot.y = 1 / (cos inner - cos outer)
    float t = std::clamp((glm::dot(-to_light, glm::vec3(light.direction_range)) - light.spot.x) * light.spot.y, 0.f, 1.f);
    a *= t * t;
  }
  radiance = glm::vec3(light.radiance) * a;
}

}  // namespace lp::ch08
