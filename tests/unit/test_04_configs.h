#pragma once
// Chapter 04's test configurations: surface points around a 2 m tube, deterministic on every
// machine (our own generator and mapping; std::uniform_real_distribution is not portable).
#include <cmath>
#include <cstdint>
#include <vector>

#include "chapters/04_neon/neon.h"

namespace lp::ch04::testing {

class Random {
 public:
  explicit Random(std::uint32_t seed) : state_(seed ? seed : 1) {}
  float uniform() {  // [0, 1)
    state_ ^= state_ << 13;
    state_ ^= state_ >> 17;
    state_ ^= state_ << 5;
    return static_cast<float>(state_ >> 8) * (1.f / 16777216.f);
  }
  glm::vec3 direction() {  // uniform on the sphere
    float z = 2.f * uniform() - 1.f, a = 6.2831853f * uniform(), r = std::sqrt(std::max(0.f, 1.f - z * z));
    return {r * std::cos(a), r * std::sin(a), z};
  }

 private:
  std::uint32_t state_;
};

inline NeonLight test_tube() {
  NeonLight l;
  l.name = "test";
  l.start = {-1, 0, 0};
  l.end = {1, 0, 0};
  l.radius = 0.02f;
  return l;
}

// Points 3 cm .. 2.5 m from the tube (denser near it), over and beyond its length; random
// normals that see at least part of the tube; eyes on the normal's side; `per_exponent`
// configurations for each Blinn-Phong exponent 1 .. 2048.
struct Config {
  NeonSurface surface;
  Terms truth;  // ground_truth_terms with 8192 samples
};
inline std::vector<Config> test_configs(int per_exponent, std::uint32_t seed = 7) {
  Random rng(seed);
  NeonLight tube = test_tube();
  std::vector<Config> out;
  for (float n : {1.f, 8.f, 32.f, 128.f, 512.f, 2048.f})
    for (int made = 0; made < per_exponent;) {
      float distance = 0.03f + 2.5f * rng.uniform() * rng.uniform();
      glm::vec3 x = glm::vec3(-2.f + 4.f * rng.uniform(), 0, 0) + rng.direction() * distance;
      glm::vec3 normal = rng.direction(), eye = rng.direction();
      if (glm::dot(eye, normal) < 0) eye = -eye;
      NeonSurface s{x, normal, eye, n};
      Terms truth = ground_truth_terms(s, tube, 8192);
      if (truth.diffuse <= 0) continue;  // the whole tube below the horizon: nothing to compare
      out.push_back({s, truth});
      ++made;
    }
  return out;
}

// Specular error relative to the truth plus 2 % of the brightest specular the tube could give
// there (the lobe's peak (n + 8) / 8 times the irradiance), so that a highlight of nearly
// nothing does not divide by nothing.
inline float specular_error(float value, const Config& c) {
  float peak = (c.surface.exponent + 8.f) / 8.f * c.truth.diffuse;
  return std::abs(value - c.truth.specular) / (c.truth.specular + 0.02f * peak);
}
inline float diffuse_error(float value, const Config& c) { return std::abs(value - c.truth.diffuse) / c.truth.diffuse; }

}  // namespace lp::ch04::testing
