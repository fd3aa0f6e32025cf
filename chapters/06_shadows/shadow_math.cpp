#include "chapters/06_shadows/shadow_math.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

#include "common/error.h"
#include "common/rng.h"

namespace lp::ch06 {

float slope_scaled_bias(float constant_texels, float slope_texels, float cos_theta, float texel_world) {
  const float c = std::clamp(cos_theta, 1e-4f, 1.f);
  const float tan_theta = std::min(std::sqrt(1.f - c * c) / c, kMaxSlope);
  return texel_world * (constant_texels + slope_texels * tan_theta);
}

glm::vec3 normal_offset(glm::vec3 position, glm::vec3 normal, float cos_theta, float texels, float texel_world) {
  const float c = std::clamp(cos_theta, 0.f, 1.f);
  return position + normal * (texels * texel_world * std::sqrt(1.f - c * c));
}

float LightFrustum::texel_world(int map_size) const {
  return std::max(box_max.x - box_min.x, box_max.y - box_min.y) / float(map_size);
}

LightFrustum fit_light_frustum(glm::vec3 direction, glm::vec3 scene_min, glm::vec3 scene_max,
                               const glm::mat4* inverse_camera_view_projection) {
  direction = glm::normalize(direction);
  const glm::vec3 up = std::abs(direction.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  const glm::vec3 centre = 0.5f * (scene_min + scene_max);
  LightFrustum f;
  f.view = glm::lookAt(centre - direction, centre, up);
  auto box_of = [&](const glm::vec3* points, int n) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (int i = 0; i < n; ++i) {
      glm::vec3 p = glm::vec3(f.view * glm::vec4(points[i], 1.f));
      lo = glm::min(lo, p), hi = glm::max(hi, p);
    }
    return std::pair{lo, hi};
  };
  glm::vec3 corners[8];
  for (int i = 0; i < 8; ++i)
    corners[i] = glm::vec3(i & 1 ? scene_max.x : scene_min.x, i & 2 ? scene_max.y : scene_min.y,
                           i & 4 ? scene_max.z : scene_min.z);
  auto [lo, hi] = box_of(corners, 8);
  if (inverse_camera_view_projection) {
    glm::vec3 view_corners[8];
    for (int i = 0; i < 8; ++i) {
      glm::vec4 p = *inverse_camera_view_projection *
                    glm::vec4(i & 1 ? 1.f : -1.f, i & 2 ? 1.f : -1.f, i & 4 ? 1.f : -1.f, 1.f);
      view_corners[i] = glm::vec3(p) / p.w;
    }
    auto [vlo, vhi] = box_of(view_corners, 8);
    // Only x and y: along the light (z) every caster of the scene stays in.
    glm::vec2 xlo = glm::max(glm::vec2(lo), glm::vec2(vlo)), xhi = glm::min(glm::vec2(hi), glm::vec2(vhi));
    if (xlo.x < xhi.x && xlo.y < xhi.y) lo.x = xlo.x, lo.y = xlo.y, hi.x = xhi.x, hi.y = xhi.y;
  }
  // A little margin so geometry on the box's faces is not clipped.
  const glm::vec3 margin = 0.01f * (hi - lo) + glm::vec3(1e-3f);
  lo -= margin, hi += margin;
  f.box_min = lo, f.box_max = hi;
  // Light view space looks down -z: near = -hi.z, far = -lo.z.
  f.projection = glm::ortho(lo.x, hi.x, lo.y, hi.y, -hi.z, -lo.z);
  return f;
}

// [cascades-cpp]
std::vector<float> cascade_splits(int count, float near, float far, float lambda) {
  if (count < 1 || count > kMaxCascades)
    throw Error("cascade_splits: between 1 and " + std::to_string(kMaxCascades) + " cascades (got " + std::to_string(count) + ")");
  if (!(near > 0.f && far > near)) throw Error("cascade_splits: needs 0 < near < far");
  if (!(lambda >= 0.f && lambda <= 1.f)) throw Error("cascade_splits: lambda must be in [0, 1]");
  std::vector<float> z(std::size_t(count) + 1);
  for (int i = 0; i <= count; ++i) {
    const float t = float(i) / float(count);
    z[std::size_t(i)] = lambda * near * std::pow(far / near, t) + (1.f - lambda) * (near + (far - near) * t);
  }
  z.front() = near, z.back() = far;  // exactly, whatever pow rounds to
  return z;
}

Sphere frustum_slice_sphere(const glm::mat4& camera_world, float yfov, float aspect, float n, float f) {
  // Half the diagonal of the slice's near and far rectangles; the centre on the axis at the depth c
  // equally far from a near and a far corner, or at the far rectangle when that is nearer.
  const float k = std::tan(yfov / 2.f) * std::sqrt(1.f + aspect * aspect);
  const float a = n * k, b = f * k;
  float c = ((f * f + b * b) - (n * n + a * a)) / (2.f * (f - n));
  c = std::clamp(c, n, f);
  const float radius = std::max(std::sqrt((c - n) * (c - n) + a * a), std::sqrt((f - c) * (f - c) + b * b));
  const glm::vec3 eye(camera_world[3]), forward = -glm::normalize(glm::vec3(camera_world[2]));
  return {eye + forward * c, radius};
}

LightFrustum fit_cascade(glm::vec3 direction, glm::vec3 scene_min, glm::vec3 scene_max, const Sphere& sphere,
                         int map_size, bool snap) {
  if (map_size < 8) throw Error("fit_cascade: a map of at least 8 texels a side");
  // The light's view and the whole scene's depth range: fit_light_frustum's, fitted to nothing.
  LightFrustum f = fit_light_frustum(direction, scene_min, scene_max);
  const float texel = 2.f * sphere.radius / float(map_size - 2);
  const float half = 0.5f * float(map_size) * texel;
  glm::vec3 centre = glm::vec3(f.view * glm::vec4(sphere.centre, 1.f));
  if (snap) centre.x = std::floor(centre.x / texel) * texel, centre.y = std::floor(centre.y / texel) * texel;
  f.box_min.x = centre.x - half, f.box_max.x = centre.x + half;
  f.box_min.y = centre.y - half, f.box_max.y = centre.y + half;
  f.projection = glm::ortho(f.box_min.x, f.box_max.x, f.box_min.y, f.box_max.y, -f.box_max.z, -f.box_min.z);
  return f;
}

CascadeChoice choose_cascade(float depth, const std::vector<float>& splits, float band) {
  CascadeChoice c;
  const int count = int(splits.size()) - 1;
  for (int i = 0; i < count; ++i)
    if (depth < splits[std::size_t(i) + 1]) {
      c.cascade = i;
      const float length = band * (splits[std::size_t(i) + 1] - splits[std::size_t(i)]);
      const float into = depth - (splits[std::size_t(i) + 1] - length);
      if (i + 1 < count && length > 0.f && into > 0.f) c.next_weight = std::min(into / length, 1.f);
      return c;
    }
  return c;
}
// [/cascades-cpp]

SpotFrustum fit_spot_frustum(glm::vec3 position, glm::vec3 direction, float outer_cone, float range, glm::vec3 scene_min,
                             glm::vec3 scene_max) {
  if (!(outer_cone > 0.f && outer_cone <= kMaxSpotCone))
    throw Error("fit_spot_frustum: the cone must be in (0, " + std::to_string(kMaxSpotCone) + "] radians (got " +
                std::to_string(outer_cone) + ")");
  direction = glm::normalize(direction);
  SpotFrustum f;
  const glm::vec3 up = std::abs(direction.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  f.view = glm::lookAt(position, position + direction, up);
  float far = 0.f;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 c(i & 1 ? scene_max.x : scene_min.x, i & 2 ? scene_max.y : scene_min.y, i & 4 ? scene_max.z : scene_min.z);
    far = std::max(far, glm::distance(c, position));
  }
  if (range > 0.f) far = std::min(far, range);
  f.far = std::max(far, 2.f * f.near);
  f.tan_cone = std::tan(outer_cone);
  f.projection = glm::perspective(2.f * outer_cone, 1.f, f.near, f.far);
  return f;
}

glm::vec2 receiver_plane_gradient(const LightFrustum& f, glm::vec3 world_normal) {
  const glm::vec3 n = glm::mat3(f.view) * world_normal;
  const float nz = std::max(n.z, 0.05f);
  return glm::vec2(n.x, n.y) / nz * glm::vec2(f.box_max - f.box_min) / f.depth_range();
}

std::vector<glm::vec2> poisson_disk(int n, unsigned long long seed, float* spacing) {
  if (n < 1 || n > kMaxPoissonTaps)
    throw Error("poisson_disk: between 1 and " + std::to_string(kMaxPoissonTaps) + " points (got " + std::to_string(n) + ")");
  Pcg32 rng(seed, 11);
  float r = 0.75f * std::sqrt(3.14159265f / float(n));
  std::vector<glm::vec2> points;
  int misses = 0;
  while (int(points.size()) < n) {
    // a uniform point of the unit disk
    const float radius = std::sqrt(rng.uniform()), angle = 6.2831853f * rng.uniform();
    const glm::vec2 p = radius * glm::vec2(std::cos(angle), std::sin(angle));
    bool free = true;
    for (const glm::vec2& q : points) free = free && glm::distance(p, q) >= r;
    if (free) {
      points.push_back(p);
      misses = 0;
    } else if (++misses >= 100 * n) {
      r *= 0.95f;
      misses = 0;
    }
  }
  if (spacing) *spacing = r;
  return points;
}

float pcss_search_radius(float receiver_depth, float angular_radius) {
  return std::max(receiver_depth, 0.f) * std::tan(angular_radius);
}

float pcss_filter_radius(float receiver_depth, float blocker_depth, float angular_radius) {
  return std::max(receiver_depth - blocker_depth, 0.f) * std::tan(angular_radius);
}

float point_light_penumbra(float light_width, float receiver_distance, float blocker_distance) {
  return light_width * (receiver_distance - blocker_distance) / blocker_distance;
}

float chebyshev_upper_bound(glm::vec2 moments, float depth, float min_variance) {
  if (depth <= moments.x) return 1.f;
  const float variance = std::max(moments.y - moments.x * moments.x, min_variance);
  const float d = depth - moments.x;
  return variance / (variance + d * d);
}

float reduce_light_bleeding(float p_max, float p_min) {
  return std::clamp((p_max - p_min) / (1.f - p_min), 0.f, 1.f);
}

float esm_filter_direct(const std::vector<float>& depths, const std::vector<float>& weights, float c) {
  float sum = 0;
  for (std::size_t i = 0; i < depths.size(); ++i) sum += weights[i] * std::exp(c * depths[i]);
  return sum;
}

float esm_filter_log(const std::vector<float>& log_values, const std::vector<float>& weights) {
  float l_max = -std::numeric_limits<float>::infinity();
  for (float l : log_values) l_max = std::max(l_max, l);
  float sum = 0;
  for (std::size_t i = 0; i < log_values.size(); ++i) sum += weights[i] * std::exp(log_values[i] - l_max);
  return l_max + std::log(sum);
}

float esm_visibility_direct(float filtered, float c, float depth) {
  return std::clamp(filtered * std::exp(-c * depth), 0.f, 1.f);
}

float esm_visibility_log(float log_filtered, float c, float depth) {
  return std::clamp(std::exp(std::min(log_filtered - c * depth, 0.f)), 0.f, 1.f);
}

// [msm-cpp]
glm::vec4 msm_moments(float z) {
  const float z2 = z * z;
  return {z, z2, z2 * z, z2 * z2};
}

// The paper's matrices, written row by row as the paper's HLSL multiplies a row vector by them;
// glm's constructor takes columns, so M * v here is the paper's mul(v, M).
glm::vec4 msm_optimize(glm::vec4 b) {
  const glm::mat4 m(-2.07224649f, 13.7948857237f, 0.105877704f, 9.7924062118f,     //
                    32.23703778f, -59.4683975703f, -1.9077466311f, -33.7652110555f,  //
                    -68.571074599f, 82.0359750338f, 9.3496555107f, 47.9456096605f,  //
                    39.3703274134f, -35.364903257f, -6.6543490743f, -23.9728048165f);
  glm::vec4 out = m * b;
  out.x += 0.035955884801f;
  return out;
}

glm::vec4 msm_unoptimize(glm::vec4 stored) {
  const glm::mat4 m(0.2227744146f, 0.1549679261f, 0.1451988946f, 0.163127443f,   //
                    0.0771972861f, 0.1394629426f, 0.2120202157f, 0.2591432266f,  //
                    0.7926986636f, 0.7963415838f, 0.7258694464f, 0.6539092497f,  //
                    0.0319417555f, -0.1722823173f, -0.2758014811f, -0.3376131734f);
  stored.x -= 0.035955884801f;
  return m * stored;
}

float msm_hamburger(glm::vec4 b, float depth, float moment_bias) {
  b = glm::mix(b, glm::vec4(0.5f), moment_bias);
  // The Hankel matrix's Cholesky factorisation, only what is needed of it.
  const float l32_d22 = -b.x * b.y + b.z;
  const float d22 = -b.x * b.x + b.y;
  const float squared_variance = -b.y * b.y + b.w;
  const float d33_d22 = squared_variance * d22 - l32_d22 * l32_d22;
  // Degenerate moments (the bias is lost to rounding near one depth): no variance left means
  // one depth, and the receiver is lit in front of it and shadowed behind.
  if (d22 <= 0.f) return depth <= b.x ? 1.f : 0.f;
  const float inv_d22 = 1.f / d22;
  const float l32 = l32_d22 * inv_d22;
  glm::vec3 c(1.f, depth, depth * depth);
  if (d33_d22 <= 0.f) {
    // A singular Hankel matrix: at most two depths, the roots of its kernel's quadratic
    // z^2 - l32 z + (l32 b.x - b.y), which is where c points as d33_d22 goes to 0.
    c = glm::vec3(l32 * b.x - b.y, -l32, 1.f);
  } else {
    // Solve B c = (1, d, d^2): forward substitution, scaling, backward substitution.
    c.y -= b.x;
    c.z -= b.y + l32 * c.y;
    c.y *= inv_d22;
    c.z *= d22 / d33_d22;
    c.y -= l32 * c.z;
    c.x -= c.y * b.x + c.z * b.y;
  }
  // A quadratic that degenerates to a line: one root r = -c.x / c.y, the other beyond 2^20 (in
  // the limit at infinity, with no weight); the weight in front of d is then (d - b.x) / (d - r).
  if (std::abs(c.y) >= 0x1p20f * std::abs(c.z)) {
    const float r = -c.x / c.y;
    return 1.f - std::clamp(r < depth ? (depth - b.x) / (depth - r) : 0.f, 0.f, 1.f);
  }
  // The other two support points: the roots of c.x + c.y z + c.z z^2.
  const float p = c.y / c.z, q = c.x / c.z;
  const float r = std::sqrt(std::max(p * p * 0.25f - q, 0.f));
  const float z1 = -p * 0.5f - r, z2 = -p * 0.5f + r;
  // The weight in front of the receiver: all of it (both roots in front), the part on z1, or none.
  const glm::vec4 sw = z2 < depth ? glm::vec4(z1, depth, 1.f, 1.f)
                       : z1 < depth ? glm::vec4(depth, z1, 0.f, 1.f)
                                    : glm::vec4(0.f);
  // (None in front when both roots lie behind: the quotient is not formed, as z1 may equal d.)
  const float quotient = sw.w > 0.f ? (sw.x * z2 - b.x * (sw.x + z2) + b.y) / ((z2 - sw.y) * (depth - z1)) : 0.f;
  const float shadow = std::clamp(sw.z + sw.w * quotient, 0.f, 1.f);
  return 1.f - shadow;
}
// [/msm-cpp]

// [sphere-in-view]
bool sphere_in_view(const glm::vec3& centre, float radius, const glm::mat4& view_projection) {
  const glm::mat4 m = glm::transpose(view_projection);  // rows of the matrix as columns
  const glm::vec4 p(centre, 1.f);
  for (int axis = 0; axis < 3; ++axis)
    for (float side : {1.f, -1.f}) {
      const glm::vec4 plane = m[3] + side * m[axis];  // w + x >= 0, w - x >= 0, ...
      const float length = glm::length(glm::vec3(plane));
      if (length > 0.f && glm::dot(plane, p) / length < -radius) return false;
    }
  return true;
}
// [/sphere-in-view]

}  // namespace lp::ch06
