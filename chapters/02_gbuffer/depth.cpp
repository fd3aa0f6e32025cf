#include "chapters/02_gbuffer/depth.h"

#include <cmath>

namespace lp::ch02 {

// [reversed-projection-body]
glm::mat4 projection_for(DepthFormat format, const FrameCamera& camera) {
  glm::mat4 p = camera.projection;
  if (format != DepthFormat::D32FS8Reversed) return p;
  // glm is column-major: p[column][row]. Clip z = a * z_view + b and w = -z_view, so
  // depth = z / w = (b - a d) / d at distance d = -z_view: 1 at the near plane, 0 at the far.
  double n = camera.znear, f = camera.zfar;
  p[2][2] = float(n / (f - n));      // a
  p[3][2] = float(n * f / (f - n));  // b
  return p;
}
// [/reversed-projection-body]

FrameCamera camera_for(DepthFormat format, const FrameCamera& camera) {
  FrameCamera c = camera;
  c.projection = projection_for(format, camera);
  return c;
}

float window_depth(DepthFormat format, const glm::mat4& view_projection, const glm::vec3& world) {
  glm::vec4 clip = view_projection * glm::vec4(world, 1.f);
  float ndc_z = clip.z / clip.w;
  return format == DepthFormat::D32FS8Reversed ? ndc_z : ndc_z * 0.5f + 0.5f;
}

float stored_depth(DepthFormat format, float d) {
  if (format != DepthFormat::D24S8) return d;
  const double steps = 16777215.0;  // 2^24 - 1
  double clamped = std::fmin(std::fmax(double(d), 0.0), 1.0);
  return float(std::round(clamped * steps) / steps);
}

// [reconstruct-cpu-body]
glm::vec3 reconstruct_position(DepthFormat format, const glm::mat4& inverse_view_projection, const glm::vec2& ndc_xy,
                               float depth) {
  float ndc_z = format == DepthFormat::D32FS8Reversed ? depth : depth * 2.f - 1.f;
  glm::vec4 world = inverse_view_projection * glm::vec4(ndc_xy, ndc_z, 1.f);
  return glm::vec3(world) / world.w;
}
// [/reconstruct-cpu-body]

glm::mat4 precise_inverse(const glm::mat4& m) { return glm::mat4(glm::inverse(glm::dmat4(m))); }

double depth_slope(DepthFormat, double n, double f, double d) { return n * f / ((f - n) * d * d); }

// [depth-error-bound]
// - Standard depth (D24 and D32F alike: window depth near 1 has float spacing 2^-24, no finer
//   than 24-bit fixed point): four steps of 2^-24 (half a step rounding into the buffer, half
//   a step rounding (z/w + 1) / 2, one for z/w, one for the rasterizer interpolating depth
//   across the triangle, one for the reconstruction's own arithmetic), turned into metres by
//   the slope of depth n f / ((f - n) d^2), and from the view axis to the ray (range / axial).
// - Reversed-Z D32F: window depth is z/w itself and keeps float's relative precision, so a
//   few roundings relative to the range: 8 * 2^-24 * range.
// - Both: world coordinates are floats, 16 roundings of 2^-24 * (magnitude + range).
double reconstruction_error_bound(DepthFormat f, double near, double far, double axial, double range, double magnitude) {
  const double eps = 5.960464477539063e-08;  // 2^-24
  double depth_term = f == DepthFormat::D32FS8Reversed ? 8 * eps * range
                                                       : 4 * eps / depth_slope(f, near, far, axial) * (range / axial);
  return depth_term + 16 * eps * (magnitude + range);
}
// [/depth-error-bound]

}  // namespace lp::ch02
