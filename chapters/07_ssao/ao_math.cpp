#include "chapters/07_ssao/ao_math.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/rng.h"

namespace lp::ch07 {

namespace {
constexpr float kPi = 3.14159265358979f;
}

bool in_kernel_hemisphere(glm::vec3 k, float slack) {
  const float len = glm::length(k);
  return len <= 1.f + slack && len >= kMinLength - slack && k.z >= kMinCosine * len - slack;
}

glm::vec3 clamp_to_kernel_hemisphere(glm::vec3 k) {
  float len = glm::length(k);
  if (!(len > 0.f)) return {0.f, 0.f, kMinLength};
  glm::vec3 d = k / len;
  if (d.z < kMinCosine) {  // onto the cone z = kMinCosine, keeping the azimuth
    glm::vec2 xy(d.x, d.y);
    float l = glm::length(xy);
    glm::vec2 dir = l > 0.f ? xy / l : glm::vec2(1.f, 0.f);
    const float s = std::sqrt(1.f - kMinCosine * kMinCosine);
    d = glm::vec3(dir * s, kMinCosine);
  }
  return d * std::clamp(len, kMinLength, 1.f);
}

// [random-kernel]
std::vector<glm::vec3> random_kernel(int samples, std::uint64_t seed) {
  Pcg32 rng(seed, 7);
  std::vector<glm::vec3> k(std::size_t(std::max(samples, 0)));
  for (int i = 0; i < samples; ++i) {
    // uniform over the hemisphere's directions with z in [kMinCosine, 1]
    float z = kMinCosine + (1.f - kMinCosine) * rng.uniform();
    float phi = 2.f * kPi * rng.uniform();
    float s = std::sqrt(1.f - z * z);
    float t = float(i) / float(samples);
    float length = kMinLength + (1.f - kMinLength) * t * t;
    k[std::size_t(i)] = glm::vec3(s * std::cos(phi), s * std::sin(phi), z) * length;
  }
  return k;
}
// [/random-kernel]

float min_spacing(const std::vector<glm::vec3>& points) {
  float best = std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < points.size(); ++i)
    for (std::size_t j = i + 1; j < points.size(); ++j) best = std::min(best, glm::distance(points[i], points[j]));
  return best;
}

// [energy-minimised]
std::vector<glm::vec3> energy_minimised_kernel(int samples, std::uint64_t seed, int iterations,
                                               std::vector<float>* spacing) {
  std::vector<glm::vec3> k = random_kernel(samples, seed);
  if (samples < 2) return k;
  // The rest length: the spacing of N points packed evenly into the half ball's volume.
  const float rest = 1.2f * std::cbrt((2.f / 3.f) * kPi / float(samples));
  std::vector<glm::vec3> force(k.size());
  if (spacing) spacing->push_back(min_spacing(k));
  for (int it = 0; it < iterations; ++it) {
    std::fill(force.begin(), force.end(), glm::vec3(0));
    for (std::size_t i = 0; i < k.size(); ++i)
      for (std::size_t j = i + 1; j < k.size(); ++j) {
        glm::vec3 d = k[i] - k[j];
        float len = glm::length(d);
        if (len >= rest) continue;  // a spring pushes only when compressed
        glm::vec3 dir = len > 1e-6f ? d / len : glm::normalize(glm::vec3(float(i) - float(j), 1.f, 0.5f));
        glm::vec3 f = 0.5f * (rest - len) * dir;
        force[i] += f;
        force[j] -= f;
      }
    for (std::size_t i = 0; i < k.size(); ++i) k[i] = clamp_to_kernel_hemisphere(k[i] + 0.25f * force[i]);
    if (spacing) spacing->push_back(min_spacing(k));
  }
  return k;
}
// [/energy-minimised]

std::vector<glm::vec3> noise_tile(std::uint64_t seed) {
  Pcg32 rng(seed, 11);
  std::vector<glm::vec3> n(16);
  for (auto& v : n) {
    float phi = 2.f * kPi * rng.uniform();
    v = glm::vec3(std::cos(phi), std::sin(phi), 0.f);
  }
  return n;
}

float bunnell_occlusion(glm::vec3 receiver, glm::vec3 receiver_normal, glm::vec3 emitter, glm::vec3 emitter_normal,
                        float emitter_area) {
  glm::vec3 v = emitter - receiver;
  float d2 = glm::dot(v, v);
  if (!(d2 > 0.f) || !(emitter_area > 0.f)) return 0.f;
  v /= std::sqrt(d2);
  float solid = 1.f - 1.f / std::sqrt(1.f + emitter_area / (kPi * d2));
  return solid * std::abs(glm::dot(emitter_normal, v)) * std::clamp(4.f * glm::dot(receiver_normal, v), 0.f, 1.f);
}

float form_factor_occlusion(glm::vec3 receiver, glm::vec3 receiver_normal, glm::vec3 emitter,
                            glm::vec3 emitter_normal, float emitter_area) {
  glm::vec3 v = emitter - receiver;
  float d2 = glm::dot(v, v);
  if (!(d2 > 0.f) || !(emitter_area > 0.f)) return 0.f;
  v /= std::sqrt(d2);
  return emitter_area * std::abs(glm::dot(emitter_normal, v)) * std::max(glm::dot(receiver_normal, v), 0.f) /
         (kPi * d2 + emitter_area);
}

float bilateral_weight(float centre_depth, float depth, glm::vec3 centre_normal, glm::vec3 normal,
                       float depth_threshold, float normal_threshold) {
  if (!(depth > 0.f) || !(centre_depth > 0.f)) return 0.f;  // the sky (or behind the camera)
  bool near = std::abs(depth - centre_depth) <= depth_threshold * centre_depth;
  bool aligned = glm::dot(centre_normal, normal) >= normal_threshold;
  return near && aligned ? 1.f : 0.f;
}

float range_weight(float radius, float gap) {
  const float t = std::clamp(radius / std::max(std::abs(gap), 1e-6f), 0.f, 1.f);
  return t * t * (3.f - 2.f * t);  // GLSL's smoothstep(0, 1, x)
}

float gtao_horizon(glm::vec3 p, glm::vec3 q, glm::vec3 normal, glm::vec3 view_vec, float low, float falloff_mul,
                   float falloff_add, float min_height) {
  const glm::vec3 delta = q - p;
  const float dist = glm::length(delta);
  if (!(dist > 0.f)) return low;
  float weight = std::clamp(dist * falloff_mul + falloff_add, 0.f, 1.f);
  if (glm::dot(delta, normal) < min_height) weight = 0.f;
  const float elevation = glm::dot(delta / dist, view_vec);
  return low + (elevation - low) * weight;  // GLSL's mix(low, elevation, weight)
}

float gtao_arc(float h, float n, float cos_n) {
  return (cos_n + 2.f * h * std::sin(n) - std::cos(2.f * h - n)) / 4.f;
}

glm::vec2 spiral_point(int i, int n) {
  const float golden = 2.39996323f;  // pi (3 - sqrt 5)
  float r = std::sqrt((float(i) + 0.5f) / float(n));
  float a = golden * float(i);
  return r * glm::vec2(std::cos(a), std::sin(a));
}

}  // namespace lp::ch07
