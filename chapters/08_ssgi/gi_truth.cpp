#include "chapters/08_ssgi/gi_truth.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "chapters/07_ssao/ao_truth.h"
#include "chapters/08_ssgi/gi_math.h"
#include "common/error.h"
#include "common/raytrace.h"

namespace lp::ch08 {

namespace {

glm::vec3 sample_srgb(const Texture& tex, glm::vec2 uv) {
  const ImageRGBA8& img = tex.image;
  int x = int(std::floor((uv.x - std::floor(uv.x)) * img.width)) % img.width;
  int y = int(std::floor((uv.y - std::floor(uv.y)) * img.height)) % img.height;
  const std::uint8_t* p = img.at(x, y);
  return glm::vec3(srgb_to_linear(p[0] / 255.f), srgb_to_linear(p[1] / 255.f), srgb_to_linear(p[2] / 255.f));
}

glm::vec3 albedo_at(const Scene& scene, const Hit& hit) {
  const Material& m = scene.materials[std::size_t(hit.material)];
  glm::vec3 albedo(m.base_color);
  if (m.base_color_texture >= 0) albedo *= sample_srgb(scene.textures[std::size_t(m.base_color_texture)], hit.uv);
  return albedo;
}

}  // namespace

// [truth-estimator]
ImageF ray_traced_indirect(const Scene& scene, const RayScene& rays, const ch03::LightSet& set,
                           const FrameCamera& camera, int width, int height, const GiTruthSettings& s) {
  if (s.samples < 1) throw Error("ray-traced indirect light: samples must be at least 1");
  if (s.bounces != 1 && s.bounces != 2) throw Error("ray-traced indirect light: bounces must be 1 or 2");
  const DirectLightSet lights = direct_lights(set);
  const auto points = surface_points(primary_hits(rays, camera, width, height));
  const glm::vec3 eye = camera.position;
  const glm::mat4 view_projection = camera.projection * camera.view;
  const float inf = std::numeric_limits<float>::infinity();

  // albedo x L1_direct leaving the surface `hit` toward a ray that arrived along `dir`
  auto leaving = [&](const Hit& hit, glm::vec3 dir, glm::vec3& normal) {
    normal = glm::dot(hit.geometric_normal, dir) < 0.f ? hit.shading_normal : -hit.shading_normal;
    const SurfacePoint at{hit.position, glm::dot(hit.geometric_normal, dir) < 0.f ? hit.geometric_normal : -hit.geometric_normal,
                          hit.error};
    auto shadowed = [&](int, glm::vec3 to_light, float distance) {
      if (!s.shadows) return false;
      return distance == inf ? rays.occluded(at.ray(to_light, inf))
                             : rays.occluded(at.ray_towards(at.position + to_light * distance));
    };
    return albedo_at(scene, hit) * direct_diffuse(lights, hit.position, normal, shadowed);
  };
  // whether the camera sees `q` (the screen-limited truth): inside the image, nothing in front
  auto on_screen = [&](glm::vec3 q) {
    glm::vec4 clip = view_projection * glm::vec4(q, 1.f);
    if (clip.w <= 0.f) return false;
    glm::vec3 ndc = glm::vec3(clip) / clip.w;
    if (std::abs(ndc.x) > 1.f || std::abs(ndc.y) > 1.f || std::abs(ndc.z) > 1.f) return false;
    glm::vec3 d = q - eye;
    float len = glm::length(d);
    return !rays.occluded(Ray{eye, d / len, 0.f, len * (1.f - 1e-4f) - position_error(q)});
  };

  return trace_image(width, height, 3, s.seed, [&](int x, int y, Pcg32& rng, float* out) {
    const auto& p = points[std::size_t(y) * width + x];
    if (!p) { out[0] = out[1] = out[2] = kTruthSky; return; }
    glm::vec3 sum(0);
    for (int i = 0; i < s.samples; ++i) {
      float u1 = rng.uniform(), u2 = rng.uniform();
      const glm::vec3 dir = ch07::cosine_direction(p->normal, u1, u2);
      const auto hit = rays.intersect(p->ray(dir, inf));
      float b1 = rng.uniform(), b2 = rng.uniform();  // drawn always: the streams stay aligned
      if (!hit) continue;  // the sky sends nothing
      if (s.screen_limited && (hit->t > s.screen_radius || !on_screen(hit->position))) continue;
      glm::vec3 normal;
      glm::vec3 l = leaving(*hit, dir, normal);
      if (s.bounces == 2) {  // one more cosine-weighted ray from the hit: its own one-bounce light
        glm::vec3 geo = glm::dot(hit->geometric_normal, dir) < 0.f ? hit->geometric_normal : -hit->geometric_normal;
        const SurfacePoint q{hit->position, geo, hit->error};
        const glm::vec3 dir2 = ch07::cosine_direction(geo, b1, b2);
        if (const auto hit2 = rays.intersect(q.ray(dir2, inf))) {
          glm::vec3 n2;
          l += albedo_at(scene, *hit) * leaving(*hit2, dir2, n2);
        }
      }
      sum += l;
    }
    sum /= float(s.samples);
    for (int c = 0; c < 3; ++c) out[c] = sum[c];
  });
}
// [/truth-estimator]

ImageF cached_ray_traced_indirect(const Scene& scene, const ch03::LightSet& lights, const FrameCamera& camera,
                                  int width, int height, const GiTruthSettings& s) {
  std::ostringstream key;
  key.precision(9);
  key << "08_ssgi indirect light v1: cosine-weighted about the geometric normal, albedo x direct diffuse at the hit, "
      << "samples " << s.samples << ", bounces " << s.bounces << ", shadows " << s.shadows << ", screen-limited "
      << s.screen_limited << " " << s.screen_radius << ", seed " << s.seed << ", lights";
  for (const auto& l : direct_lights(lights).lights)
    for (const glm::vec4* v : {&l.position_type, &l.direction_range, &l.radiance, &l.spot})
      key << " " << v->x << " " << v->y << " " << v->z << " " << v->w;
  for (float c : direct_lights(lights).cut) key << " cut " << c;
  return cached_image(truth_key(scene, camera, width, height, key.str()), [&] {
    RayScene rays(scene);
    return ray_traced_indirect(scene, rays, lights, camera, width, height, s);
  });
}

GiErrors gi_errors(const ImageF& estimate, const ImageF& truth, const std::vector<std::uint8_t>* mask) {
  if (estimate.width != truth.width || estimate.height != truth.height)
    throw Error("gi_errors: the images differ in size");
  GiErrors e;
  double sum_t = 0, sum_e = 0;
  for (int y = 0; y < truth.height; ++y)
    for (int x = 0; x < truth.width; ++x) {
      if (truth.at(x, y, 0) < 0.f) continue;
      if (mask && !(*mask)[std::size_t(y) * truth.width + x]) continue;
      for (int c = 0; c < 3; ++c) {
        double t = truth.at(x, y, c), v = estimate.at(x, y, c);
        e.mean_abs += std::abs(v - t);
        sum_t += t;
        sum_e += v;
      }
      ++e.pixels;
    }
  if (e.pixels) {
    const double n = 3.0 * double(e.pixels);
    e.mean_abs /= n;
    e.mean_truth = sum_t / n;
    e.mean_estimate = sum_e / n;
    e.relative = sum_t > 0 ? e.mean_abs / e.mean_truth : 0;
    e.captured = sum_t > 0 ? sum_e / sum_t : 0;
  }
  return e;
}

ImageF gi_error_map(const ImageF& estimate, const ImageF& truth) {
  ImageF m = ImageF::blank(truth.width, truth.height, 1);
  for (int y = 0; y < truth.height; ++y)
    for (int x = 0; x < truth.width; ++x) {
      if (truth.at(x, y, 0) < 0.f) continue;
      float d = 0;
      for (int c = 0; c < 3; ++c) d += std::abs(estimate.at(x, y, c) - truth.at(x, y, c));
      m.at(x, y, 0) = d / 3.f;
    }
  return m;
}

}  // namespace lp::ch08
