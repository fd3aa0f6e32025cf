#include "chapters/06_shadows/shadow_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "common/error.h"

namespace lp::ch06 {

namespace {

// Every image a metric compares has the same size, and the reference its three channels.
void check_pair(const ImageF& visibility, const ImageF& reference, const char* what) {
  if (reference.channels < 3)
    throw Error(std::string(what) + ": the reference needs 3 channels (visibility, soft, mask), has " +
                std::to_string(reference.channels));
  if (visibility.width != reference.width || visibility.height != reference.height || visibility.channels < 1)
    throw Error(std::string(what) + ": the method's image is " + std::to_string(visibility.width) + "x" +
                std::to_string(visibility.height) + ", the reference " + std::to_string(reference.width) + "x" +
                std::to_string(reference.height));
}
void check_exclude(const std::vector<bool>* exclude, const ImageF& reference, const char* what) {
  if (exclude && exclude->size() != std::size_t(reference.width) * std::size_t(reference.height))
    throw Error(std::string(what) + ": the excluded pixels' mask has " + std::to_string(exclude->size()) +
                " entries, the image " + std::to_string(std::size_t(reference.width) * std::size_t(reference.height)));
}
std::size_t index(const ImageF& image, int x, int y) { return std::size_t(y) * std::size_t(image.width) + std::size_t(x); }

}  // namespace

std::vector<bool> outside_method_mask(const ImageF& v) {
  std::vector<bool> out(std::size_t(v.width) * std::size_t(v.height), false);
  if (v.channels < 3) return out;  // no colour, no blue
  for (int y = 0; y < v.height; ++y)
    for (int x = 0; x < v.width; ++x) out[index(v, x, y)] = v.at(x, y, 2) > 0.3f && v.at(x, y, 0) < 0.2f;
  return out;
}

std::vector<bool> penumbra_pixels(const ImageF& reference, int channel, int band) {
  if (channel < 0 || channel >= reference.channels || reference.channels < 3)
    throw Error("penumbra_pixels: channel " + std::to_string(channel) + " of an image with " +
                std::to_string(reference.channels) + " channels (the mask is channel 2)");
  band = std::clamp(band, 0, 64);  // bounded work per pixel
  const int w = reference.width, h = reference.height;
  auto masked = [&](int x, int y) { return reference.at(x, y, 2) > 0.5f; };
  // Strictly between 0 and 1: any value a ray count can give other than none or all.
  std::vector<bool> inside(std::size_t(w) * std::size_t(h), false);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float v = reference.at(x, y, channel);
      inside[index(reference, x, y)] = masked(x, y) && v > 0.f && v < 1.f;
    }
  // Widened by `band` pixels: a row pass, then a column pass (a square of side 2 band + 1).
  std::vector<bool> rows(inside.size(), false), out(inside.size(), false);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int dx = -band; dx <= band && !rows[index(reference, x, y)]; ++dx)
        if (x + dx >= 0 && x + dx < w && inside[index(reference, x + dx, y)]) rows[index(reference, x, y)] = true;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!masked(x, y)) continue;
      for (int dy = -band; dy <= band && !out[index(reference, x, y)]; ++dy)
        if (y + dy >= 0 && y + dy < h && rows[index(reference, x, y + dy)]) out[index(reference, x, y)] = true;
    }
  return out;
}

PenumbraError penumbra_error(const ImageF& visibility, const ImageF& reference, int channel,
                             const std::vector<bool>* exclude, int band) {
  check_pair(visibility, reference, "penumbra_error");
  check_exclude(exclude, reference, "penumbra_error");
  const std::vector<bool> penumbra = penumbra_pixels(reference, channel, band);
  PenumbraError e;
  double sum = 0, signed_sum = 0;
  for (int y = 0; y < reference.height; ++y)
    for (int x = 0; x < reference.width; ++x) {
      const std::size_t i = index(reference, x, y);
      if (!penumbra[i] || (exclude && (*exclude)[i])) continue;
      const double d = double(visibility.at(x, y, 0)) - double(reference.at(x, y, channel));
      sum += std::abs(d), signed_sum += d;
      ++e.pixels;
    }
  if (e.pixels) e.mean_abs = sum / double(e.pixels), e.mean_signed = signed_sum / double(e.pixels);
  return e;
}

LightLeak light_leak(const ImageF& visibility, const ImageF& truth, const std::vector<bool>* exclude, float threshold) {
  check_pair(visibility, truth, "light_leak");
  check_exclude(exclude, truth, "light_leak");
  LightLeak l;
  for (int y = 0; y < truth.height; ++y)
    for (int x = 0; x < truth.width; ++x) {
      if (truth.at(x, y, 2) < 0.5f || truth.at(x, y, 1) > 0.f || (exclude && (*exclude)[index(truth, x, y)])) continue;
      ++l.full_shadow;
      l.leaking += visibility.at(x, y, 0) > threshold;
    }
  return l;
}

KernelFootprint kernel_footprint(const LightFrustum& frustum, int map_size, int kernel) {
  if (map_size < 1 || kernel < 1)
    throw Error("kernel_footprint: map size " + std::to_string(map_size) + " and kernel " + std::to_string(kernel) +
                " must be positive");
  const glm::mat4 world = glm::inverse(frustum.view);  // light view space -> world: its axes
  KernelFootprint f;
  f.axis_u = glm::normalize(glm::vec3(world[0]));
  f.axis_v = glm::normalize(glm::vec3(world[1]));
  f.to_sun = glm::normalize(glm::vec3(world[2]));  // the light view looks down -z: +z is toward the sun
  f.width_u = float(kernel) * (frustum.box_max.x - frustum.box_min.x) / float(map_size);
  f.width_v = float(kernel) * (frustum.box_max.y - frustum.box_min.y) / float(map_size);
  return f;
}

// [filtered-truth-cpp]
ImageF filtered_hard_truth(const RayScene& rays, const FrameCamera& camera, int width, int height,
                           const KernelFootprint& fp, int strata, std::uint64_t seed) {
  check_image_size(width, height, "filtered_hard_truth");
  if (strata < 1 || strata > 32) throw Error("filtered_hard_truth: strata must be between 1 and 32, got " + std::to_string(strata));
  if (!(fp.width_u >= 0.f && fp.width_v >= 0.f && std::isfinite(fp.width_u) && std::isfinite(fp.width_v)))
    throw Error("filtered_hard_truth: the footprint's widths must be finite and not negative");
  const std::vector<std::optional<SurfacePoint>> points = surface_points(primary_hits(rays, camera, width, height));
  const glm::vec3 to_sun = glm::normalize(fp.to_sun);
  const float far = 1e30f;
  return trace_image(width, height, 3, seed, [&](int x, int y, Pcg32& rng, float* out) {
    const auto& point = points[std::size_t(y) * std::size_t(width) + std::size_t(x)];
    if (!point) return;
    const float facing = glm::dot(point->normal, to_sun);
    if (facing <= 0.f) return;  // facing away: not in the mask, as shadow_truth's
    out[2] = 1.f;
    // Along the light onto the receiver's plane: p + o + t to_sun with n . (o + t to_sun) = 0.
    // The slope is capped at 20:1 as receiver_plane_gradient caps it.
    const float n_dot_l = std::max(facing, 0.05f);
    int lit = 0;
    for (int j = 0; j < strata; ++j)
      for (int i = 0; i < strata; ++i) {
        const float u = ((float(i) + rng.uniform()) / float(strata) - 0.5f) * fp.width_u;
        const float v = ((float(j) + rng.uniform()) / float(strata) - 0.5f) * fp.width_v;
        const glm::vec3 o = u * fp.axis_u + v * fp.axis_v;
        SurfacePoint q = *point;
        q.position = point->position + o - to_sun * (glm::dot(point->normal, o) / n_dot_l);
        lit += !rays.occluded(q.ray(to_sun, far));
      }
    out[0] = out[1] = float(lit) / float(strata * strata);
  });
}
// [/filtered-truth-cpp]

ImageF cached_filtered_hard_truth(const Scene& scene, const RayScene& rays, const FrameCamera& camera, int width,
                                  int height, const KernelFootprint& fp, int strata) {
  char text[512];
  std::snprintf(text, sizeof text,
                "06_shadows filtered hard truth v1: to sun %.9g %.9g %.9g u %.9g %.9g %.9g v %.9g %.9g %.9g widths %.9g "
                "%.9g strata %d",
                fp.to_sun.x, fp.to_sun.y, fp.to_sun.z, fp.axis_u.x, fp.axis_u.y, fp.axis_u.z, fp.axis_v.x, fp.axis_v.y,
                fp.axis_v.z, fp.width_u, fp.width_v, strata);
  return cached_image(truth_key(scene, camera, width, height, text),
                      [&] { return filtered_hard_truth(rays, camera, width, height, fp, strata); });
}

}  // namespace lp::ch06
