#include "chapters/09_clustered/density.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "common/error.h"

namespace lp::ch09 {

std::vector<Light> scaled_lights(std::vector<Light> lights, float s) {
  if (!std::isfinite(s) || s <= 0.f) throw Error("scaled lights: the scale must be finite and > 0, not " + std::to_string(s));
  for (Light& l : lights) {
    if (l.type == LightType::Directional) continue;
    l.range *= s;  // 0 (unbounded) stays 0: its cut is set by the intensity alone, and scales with sqrt(s^2)
    l.intensity *= s * s;
  }
  return lights;
}

std::vector<Camera> views_along(const Camera& start, int count, float step) {
  std::vector<Camera> views;
  glm::vec3 forward = -glm::vec3(start.world[2]);
  forward.y = 0.f;
  forward = glm::length(forward) > 1e-6f ? glm::normalize(forward) : glm::vec3(0, 0, -1);
  for (int k = 0; k < count; ++k) {
    Camera c = start;
    c.name = start.name + "+" + std::to_string(k);
    c.world = glm::translate(glm::mat4(1.f), forward * (step * float(k))) * start.world;
    views.push_back(c);
  }
  return views;
}

// [fit-density]
DensityFit fit_density(double target, float start, const std::function<double(float)>& measure, double tolerance,
                       int max_steps) {
  if (!(target > 0) || !std::isfinite(target)) throw Error("fit_density: the target density must be > 0");
  DensityFit fit;
  double s = start, m = measure(float(s));
  double prev_s = 0, prev_m = 0;
  // The bracket: the largest scale measured below the target and the smallest above it (0: none yet).
  double lo_s = 0, lo_m = 0, hi_s = 0, hi_m = 0;
  auto bracket = [&](double bs, double bm) {
    if (bm < target && bs > lo_s) lo_s = bs, lo_m = bm;
    if (bm > target && (hi_s == 0 || bs < hi_s)) hi_s = bs, hi_m = bm;
  };
  bracket(s, m);
  fit = {float(s), m, 1, std::abs(m / target - 1) <= tolerance};
  while (!fit.met && fit.steps < max_steps) {
    double next;
    if (lo_s > 0 && hi_s > 0) {
      // [fit-bracket]
      // Bracketed: the secant between the bracket's ends in log space (density ~ s^p with the p
      // they show, however steep), or the bracket's middle where that is not strictly inside it.
      // A secant from the last two points alone overshoots a steep density back and forth.
      next = std::sqrt(lo_s * hi_s);
      if (lo_m > 0) {
        const double p = std::log(hi_m / lo_m) / std::log(hi_s / lo_s);
        const double secant = lo_s * std::pow(target / lo_m, 1.0 / p);
        if (secant > lo_s && secant < hi_s) next = secant;
      }
      // [/fit-bracket]
    } else {
      double p = 3.0;  // density ~ s^p: 3 for lights small next to the scene
      if (prev_s > 0 && prev_m > 0 && m > 0 && std::abs(std::log(s / prev_s)) > 1e-6)
        p = std::clamp(std::log(m / prev_m) / std::log(s / prev_s), 0.5, 6.0);
      const double ratio = m > 0 ? std::pow(target / m, 1.0 / p) : 4.0;  // nothing lit: lights 4x as large
      next = s * std::clamp(ratio, 0.125, 8.0);
    }
    prev_s = s;
    prev_m = m;
    s = next;
    m = measure(float(s));
    bracket(s, m);
    ++fit.steps;
    if (std::abs(m / target - 1) < std::abs(fit.density / target - 1)) {
      fit.scale = float(s);
      fit.density = m;
    }
    fit.met = std::abs(fit.density / target - 1) <= tolerance;
  }
  return fit;
}
// [/fit-density]

double quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const double at = std::clamp(q, 0.0, 1.0) * double(values.size() - 1);
  const std::size_t i = std::size_t(std::floor(at));
  const double f = at - double(i);
  return i + 1 < values.size() ? values[i] * (1 - f) + values[i + 1] * f : values[i];
}

}  // namespace lp::ch09
