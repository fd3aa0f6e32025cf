#include "chapters/03_light_volumes/light_radius.h"

#include <algorithm>
#include <cmath>

#include "chapters/01_forward/blinn_phong.h"
#include "common/error.h"

namespace lp::ch03 {

// [light-radius]
// Without a range the window is 1 and peak / d^2 = t gives d = sqrt(peak / t) =: r0.
// With a range R the window is (1 - (d/R)^4)^2; taking the square root of both sides of
// peak (1 - (d/R)^4)^2 / d^2 = t (everything positive for d < R) leaves
//
//     1 - (d/R)^4 = d / r0   or, with x = d/R and a = R/r0,   f(x) = x^4 + a x - 1 = 0.
//
// f rises from f(0) = -1 and is convex, so it has one root in (0, 1), below both 1 and
// 1/a (where f > 0). Newton's method started from min(1, 1/a) walks down onto the root and
// never passes it: every step is already a radius that encloses the light.
float light_radius(float peak, float range, float threshold) {
  if (!(threshold > 0) || !std::isfinite(threshold)) throw Error("the light cut-off threshold must be positive");
  if (!(peak > 0) || !std::isfinite(peak)) return 0.f;  // no light, no volume
  const double r0 = std::sqrt(double(peak) / threshold);
  // Rounding to float, and the shader's float arithmetic, stay within a few parts in 10^7:
  // a margin of 10^-6 keeps the light inside its volume.
  constexpr double kMargin = 1.0 + 1e-6;
  if (!(range > 0)) return static_cast<float>(r0 * kMargin);  // unbounded inverse square
  const double a = range / r0;
  double x = std::min(1.0, 1.0 / a);
  for (int i = 0; i < 64; ++i) {
    const double step = (x * x * x * x + a * x - 1.0) / (4.0 * x * x * x + a);
    x -= step;
    if (step < 1e-12) break;
  }
  return static_cast<float>(x * range * kMargin);
}
// [/light-radius]

float light_radius(const Light& light, float threshold) {
  const float peak = std::max({light.color.r, light.color.g, light.color.b}) * light.intensity;
  return light_radius(peak, light.range, threshold);
}

// [peak-reflectance]
float peak_reflectance(const Scene& scene) {
  float peak = 1.f;
  for (const Material& m : scene.materials) {
    auto largest = [](const glm::vec3& c) { return std::max({c.r, c.g, c.b, 0.f}); };
    float lobe = (ch01::exponent_from_roughness(m.roughness) + 8.f) / 8.f;
    peak = std::max(peak, largest(glm::vec3(m.base_color)) + largest(m.specular_color) * lobe);
  }
  return peak;
}
// [/peak-reflectance]

}  // namespace lp::ch03
