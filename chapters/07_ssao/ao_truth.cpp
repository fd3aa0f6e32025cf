#include "chapters/07_ssao/ao_truth.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/error.h"
#include "common/raytrace.h"

namespace lp::ch07 {

glm::vec3 cosine_direction(glm::vec3 n, float u1, float u2) {
  float sign = std::copysign(1.f, n.z);
  float a = -1.f / (sign + n.z);
  float c = n.x * n.y * a;
  glm::vec3 t(1.f + sign * n.x * n.x * a, sign * c, -sign * n.x), b(c, sign + n.y * n.y * a, -n.y);
  float r = std::sqrt(u1), phi = 6.28318531f * u2;
  float z = std::sqrt(std::max(0.f, 1.f - u1));
  return glm::normalize(r * std::cos(phi) * t + r * std::sin(phi) * b + z * n);
}

// [truth-estimator]
ImageF ray_traced_ao(const RayScene& rays, const FrameCamera& camera, int width, int height, const AoTruthSettings& s) {
  if (s.samples < 1) throw Error("ray-traced AO: samples must be at least 1");
  if (!(s.radius > 0.f)) throw Error("ray-traced AO: the radius must be positive");
  // the points the rasterised pixels see, each with its triangle's normal turned to the camera
  const auto points = surface_points(primary_hits(rays, camera, width, height));
  return trace_image(width, height, 1, s.seed, [&](int x, int y, Pcg32& rng, float* out) {
    const auto& p = points[std::size_t(y) * width + x];
    if (!p) { out[0] = kTruthSky; return; }
    int open = 0;
    for (int i = 0; i < s.samples; ++i) {
      float u1 = rng.uniform(), u2 = rng.uniform();
      open += !rays.occluded(p->ray(cosine_direction(p->normal, u1, u2), s.radius));
    }
    out[0] = float(open) / float(s.samples);
  });
}
// [/truth-estimator]

ImageF cached_ray_traced_ao(const Scene& scene, const FrameCamera& camera, int width, int height,
                            const AoTruthSettings& s) {
  std::ostringstream key;
  key << "07_ssao ambient occlusion: cosine-weighted about the geometric normal, binary visibility, radius "
      << s.radius << ", samples " << s.samples << ", seed " << s.seed;
  return cached_image(truth_key(scene, camera, width, height, key.str()), [&] {
    RayScene rays(scene);
    return ray_traced_ao(rays, camera, width, height, s);
  });
}

AoErrors ao_errors(const ImageF& ao, const ImageF& truth) {
  if (ao.width != truth.width || ao.height != truth.height)
    throw Error("ao_errors: the images differ in size");
  AoErrors e;
  for (int y = 0; y < ao.height; ++y)
    for (int x = 0; x < ao.width; ++x) {
      float t = truth.at(x, y, 0);
      if (t < 0.f) continue;
      double d = double(ao.at(x, y, 0)) - t;
      e.mean_abs += std::abs(d);
      e.mean_sq += d * d;
      e.mean_signed += d;
      e.max_abs = std::max(e.max_abs, std::abs(d));
      ++e.pixels;
    }
  if (e.pixels) {
    e.mean_abs /= double(e.pixels);
    e.mean_sq /= double(e.pixels);
    e.mean_signed /= double(e.pixels);
  }
  return e;
}

std::vector<float> ao_error_map(const ImageF& ao, const ImageF& truth) {
  std::vector<float> m(std::size_t(ao.width) * ao.height, 0.f);
  for (int y = 0; y < ao.height; ++y)
    for (int x = 0; x < ao.width; ++x)
      if (truth.at(x, y, 0) >= 0.f) m[std::size_t(y) * ao.width + x] = std::abs(ao.at(x, y, 0) - truth.at(x, y, 0));
  return m;
}

}  // namespace lp::ch07
