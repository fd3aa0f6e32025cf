#pragma once
// A tiny cosine-weighted ambient-occlusion estimator, only to hold common/raytrace.h to
// analytic answers (tests) and to give its throughput benchmark a realistic ray load.
// Chapter 07 owns the real one; this is not it.
#include <cmath>

#include "common/raytrace.h"

namespace lp::test {

// A right-handed orthonormal basis around unit n (Duff et al. 2017, branchless).
inline void basis(glm::vec3 n, glm::vec3& t, glm::vec3& b) {
  float sign = std::copysign(1.f, n.z);
  float a = -1.f / (sign + n.z);
  float c = n.x * n.y * a;
  t = glm::vec3(1.f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = glm::vec3(c, sign + n.y * n.y * a, -n.y);
}

// Malley's method: a uniform point of the unit disk, lifted onto the hemisphere, has the
// density cos(theta) / pi. The disk point's coordinates are the direction's tangent ones.
inline glm::vec3 cosine_direction(glm::vec3 n, float u1, float u2) {
  float r = std::sqrt(u1), phi = 6.2831853f * u2;
  float x = r * std::cos(phi), y = r * std::sin(phi), z = std::sqrt(std::max(0.f, 1.f - u1));
  glm::vec3 t, b;
  basis(n, t, b);
  return glm::normalize(x * t + y * b + z * n);
}

// How many of `samples` cosine-weighted rays of length `radius` from p hit something.
inline int occluded_rays(const RayScene& scene, const SurfacePoint& p, float radius, int samples, Pcg32& rng) {
  int hits = 0;
  for (int i = 0; i < samples; ++i) {
    float u1 = rng.uniform(), u2 = rng.uniform();
    hits += scene.occluded(p.ray(cosine_direction(p.normal, u1, u2), radius));
  }
  return hits;
}

}  // namespace lp::test
