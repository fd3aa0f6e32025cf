#include "chapters/06_shadows/shadow_truth.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace lp::ch06 {

glm::vec3 sample_cone(glm::vec3 axis, float angular_radius, float u, float v) {
  axis = glm::normalize(axis);
  const glm::vec3 helper = std::abs(axis.x) > 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  const glm::vec3 t = glm::normalize(glm::cross(helper, axis)), b = glm::cross(axis, t);
  const float cos_theta = 1.f - u * (1.f - std::cos(angular_radius));
  const float sin_theta = std::sqrt(std::max(0.f, 1.f - cos_theta * cos_theta));
  const float phi = 6.2831853f * v;
  return glm::normalize(axis * cos_theta + (t * std::cos(phi) + b * std::sin(phi)) * sin_theta);
}

// [truth]
ImageF shadow_truth(const Scene&, const RayScene& rays, const FrameCamera& camera, int width, int height,
                    glm::vec3 sun_direction, const TruthSettings& settings) {
  const glm::vec3 to_sun = -glm::normalize(sun_direction);
  const std::vector<std::optional<SurfacePoint>> points = surface_points(primary_hits(rays, camera, width, height));
  const int strata = std::max(1, int(std::sqrt(double(settings.samples))));
  const float far = 1e30f;  // the sun is at infinity: any surface along the ray shadows
  return trace_image(width, height, 3, settings.seed, [&](int x, int y, Pcg32& rng, float* out) {
    const auto& point = points[std::size_t(y) * std::size_t(width) + std::size_t(x)];
    if (!point || glm::dot(point->normal, to_sun) <= 0.f) return;  // sky, or facing away: not in the mask
    out[2] = 1.f;
    out[0] = rays.occluded(point->ray(to_sun, far)) ? 0.f : 1.f;
    // Soft: stratified over the disk (strata x strata cells, one jittered ray each), the rest random.
    int lit = 0;
    for (int i = 0; i < settings.samples; ++i) {
      float u = rng.uniform(), v = rng.uniform();
      if (i < strata * strata) u = (float(i % strata) + u) / float(strata), v = (float(i / strata) + v) / float(strata);
      const glm::vec3 d = sample_cone(to_sun, settings.angular_radius, u, v);
      if (glm::dot(point->normal, d) > 0.f && !rays.occluded(point->ray(d, far))) ++lit;
    }
    out[1] = float(lit) / float(settings.samples);
  });
}
// [/truth]

ImageF spot_shadow_truth(const RayScene& rays, const FrameCamera& camera, int width, int height, const Light& spot) {
  const std::vector<std::optional<SurfacePoint>> points = surface_points(primary_hits(rays, camera, width, height));
  const glm::vec3 axis = spot.type == LightType::Spot ? glm::normalize(spot.direction) : glm::vec3(0, 0, -1);
  const float cos_cone = std::cos(spot.outer_cone);
  return trace_image(width, height, 3, 0, [&](int x, int y, Pcg32&, float* out) {
    const auto& point = points[std::size_t(y) * std::size_t(width) + std::size_t(x)];
    if (!point) return;
    const glm::vec3 to_light = spot.position - point->position;
    const float distance = glm::length(to_light);
    if (distance <= 0.f || glm::dot(point->normal, to_light) <= 0.f) return;  // facing away
    if (spot.type == LightType::Spot && glm::dot(-to_light / distance, axis) < cos_cone) return;  // outside the cone
    if (spot.range > 0.f && distance > spot.range) return;
    out[2] = 1.f;
    out[0] = out[1] = rays.occluded(point->ray_towards(spot.position)) ? 0.f : 1.f;
  });
}

ImageF cached_shadow_truth(const Scene& scene, const RayScene& rays, const FrameCamera& camera, int width, int height,
                           glm::vec3 sun_direction, const TruthSettings& settings) {
  char text[256];
  std::snprintf(text, sizeof text, "06_shadows sun visibility v1: direction %.9g %.9g %.9g radius %.9g samples %d seed %llu",
                sun_direction.x, sun_direction.y, sun_direction.z, settings.angular_radius, settings.samples,
                (unsigned long long)settings.seed);
  return cached_image(truth_key(scene, camera, width, height, text),
                      [&] { return shadow_truth(scene, rays, camera, width, height, sun_direction, settings); });
}

VisibilityError visibility_error(const ImageF& visibility, const ImageF& truth, int channel,
                                 const std::vector<bool>* exclude) {
  std::vector<double> errors;
  for (int y = 0; y < truth.height; ++y)
    for (int x = 0; x < truth.width; ++x) {
      if (truth.at(x, y, 2) < 0.5f) continue;
      if (exclude && (*exclude)[std::size_t(y) * std::size_t(truth.width) + std::size_t(x)]) continue;
      errors.push_back(std::abs(double(visibility.at(x, y, 0)) - double(truth.at(x, y, channel))));
    }
  VisibilityError e;
  e.pixels = errors.size();
  if (errors.empty()) return e;
  double sum = 0;
  std::size_t wrong = 0;
  for (double v : errors) sum += v, wrong += v > 0.5;
  e.mean_abs = sum / double(errors.size());
  e.wrong = double(wrong) / double(errors.size());
  std::sort(errors.begin(), errors.end());
  e.p99 = errors[std::min(errors.size() - 1, std::size_t(0.99 * double(errors.size())))];
  return e;
}

Flips visibility_flips(const ImageF& method_a, const ImageF& method_b, const ImageF& truth_a, const ImageF& truth_b) {
  auto blue = [](const ImageF& v, int x, int y) { return v.at(x, y, 2) > 0.3f && v.at(x, y, 0) < 0.2f; };
  Flips f;
  for (int y = 0; y < truth_a.height; ++y)
    for (int x = 0; x < truth_a.width; ++x) {
      if (truth_a.at(x, y, 2) < 0.5f || truth_b.at(x, y, 2) < 0.5f || blue(method_a, x, y) || blue(method_b, x, y)) continue;
      ++f.pixels;
      f.method += (method_a.at(x, y, 0) > 0.5f) != (method_b.at(x, y, 0) > 0.5f);
      f.truth += (truth_a.at(x, y, 0) > 0.5f) != (truth_b.at(x, y, 0) > 0.5f);
    }
  return f;
}

std::vector<bool> hard_edge_pixels(const ImageF& truth, int radius) {
  std::vector<bool> edge(std::size_t(truth.width) * std::size_t(truth.height), false);
  for (int y = 0; y < truth.height; ++y)
    for (int x = 0; x < truth.width; ++x) {
      bool lit = false, dark = false, outside = false;
      for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
          const int u = x + dx, v = y + dy;
          if (u < 0 || v < 0 || u >= truth.width || v >= truth.height) continue;
          if (truth.at(u, v, 2) < 0.5f) outside = true;
          else (truth.at(u, v, 0) > 0.5f ? lit : dark) = true;
        }
      edge[std::size_t(y) * std::size_t(truth.width) + std::size_t(x)] = (lit && dark) || outside;
    }
  return edge;
}

}  // namespace lp::ch06
