#include "chapters/09_clustered/cluster_grid.h"

#include <algorithm>
#include <cmath>

namespace lp::ch09 {

Grid grid_of_tiles(int width, int height, int tile_px, int slices, float znear, float zfar) {
  Grid g;
  g.width = width;
  g.height = height;
  g.tile_w = g.tile_h = std::max(tile_px, 1);
  g.tiles_x = (width + g.tile_w - 1) / g.tile_w;
  g.tiles_y = (height + g.tile_h - 1) / g.tile_h;
  g.slices = std::max(slices, 1);
  g.znear = znear;
  g.zfar = zfar;
  return g;
}

Grid grid_of_counts(int width, int height, int nx, int ny, int slices, float znear, float zfar) {
  Grid g;
  g.width = width;
  g.height = height;
  nx = std::clamp(nx, 1, std::max(width, 1));
  ny = std::clamp(ny, 1, std::max(height, 1));
  g.tile_w = (width + nx - 1) / nx;
  g.tile_h = (height + ny - 1) / ny;
  g.tiles_x = (width + g.tile_w - 1) / g.tile_w;  // 16 over 20 pixels: tiles of 2, 10 of them
  g.tiles_y = (height + g.tile_h - 1) / g.tile_h;
  g.slices = std::max(slices, 1);
  g.znear = znear;
  g.zfar = zfar;
  return g;
}

// [near-slice]
// With a near slice: slice 0 is znear .. near_slice, slices 1 .. S - 1 exponential beyond it.
static float slice_start_near(const Grid& g, int k) {
  if (k <= 0) return g.znear;
  if (k >= g.slices) return g.zfar;
  return g.near_slice * std::pow(g.zfar / g.near_slice, float(k - 1) / float(g.slices - 1));
}

static int slice_of_near(const Grid& g, float view_depth) {
  if (view_depth < g.near_slice) return 0;
  const float t = std::log(view_depth / g.near_slice) / std::log(g.zfar / g.near_slice);
  return std::clamp(1 + int(std::floor(t * float(g.slices - 1))), 1, g.slices - 1);
}
// [/near-slice]

// [slices]
float slice_start(const Grid& g, int k) {
  if (g.has_near_slice()) return slice_start_near(g, k);
  if (k <= 0) return g.znear;
  if (k >= g.slices) return g.zfar;
  return g.znear * std::pow(g.zfar / g.znear, float(k) / float(g.slices));
}

int slice_of(const Grid& g, float view_depth) {
  if (g.has_near_slice()) return slice_of_near(g, view_depth);
  const float t = std::log(std::max(view_depth, g.znear) / g.znear) / std::log(g.zfar / g.znear);
  return std::clamp(int(std::floor(t * float(g.slices))), 0, g.slices - 1);
}
// [/slices]

Box cell_box(const FrameCamera& camera, const Grid& g, int x0, int y0, int x1, int y1, float d0, float d1) {
  d0 *= 1.f - kDepthPad;
  d1 *= 1.f + kDepthPad;
  const glm::mat4& p = camera.projection;
  Box b{glm::vec3(1e30f), glm::vec3(-1e30f)};
  for (float d : {d0, d1})
    for (int x : {x0, x1})
      for (int y : {y0, y1}) {
        // clip = P * (vx, vy, -d, 1), w = d: ndc_x = (P00 vx - P20 d) / d.
        const float nx = float(x) / float(g.width) * 2.f - 1.f, ny = float(y) / float(g.height) * 2.f - 1.f;
        const glm::vec3 v(d * (nx + p[2][0]) / p[0][0], d * (ny + p[2][1]) / p[1][1], -d);
        b.lo = glm::min(b.lo, v);
        b.hi = glm::max(b.hi, v);
      }
  return b;
}

Box cluster_box(const FrameCamera& camera, const Grid& g, int tx, int ty, int slice) {
  return cell_box(camera, g, tx * g.tile_w, ty * g.tile_h, std::min((tx + 1) * g.tile_w, g.width),
                  std::min((ty + 1) * g.tile_h, g.height), slice_start(g, slice), slice_start(g, slice + 1));
}

// [sphere-box]
bool sphere_meets_box(const glm::vec3& centre, float radius, const Box& box) {
  const glm::vec3 nearest = glm::clamp(centre, box.lo, box.hi);
  const glm::vec3 d = centre - nearest;
  const float r = radius * (1.f + 1e-5f) + 1e-6f;
  return glm::dot(d, d) <= r * r;
}
// [/sphere-box]

float capsule_rounding_margin(const glm::vec3& a, const glm::vec3& b, float radius, const Box& box, float eye_distance) {
  auto size = [](const glm::vec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); };
  const float s = std::max({size(a), size(b), size(box.lo), size(box.hi)}) + radius + eye_distance;
  return kCapsuleRoundingUlps * std::ldexp(1.f, -24) * s;
}

// Why 18 units of roundoff cover the slab test: were the segment's point at t* within the box
// grown by the radius, it is inside every slab of the box grown by m more, by m / |d_k| in t on
// each side. A computed end (lo_k - a_k) / d_k near t* (|t| <= 2) errs by at most u |lo_k| + u
// |lo_k - a_k| in its numerator, u |d_k| in d_k and 2.5 u in the division: under
// (2 u S + 8 u |d_k|) / |d_k| with |d_k| <= 2 S, so under 18 u S / |d_k|, less than m / |d_k|:
// every slab's computed interval still holds t*, and t0 <= t1. A parallel slab (d_k exactly
// 0) compares a_k with bounds that err by u S. So the margin holds this test's rounding.
bool capsule_meets_box(const glm::vec3& a, const glm::vec3& b, float radius, const Box& box, float eye_distance) {
  const float r = radius * (1.f + 1e-5f) + 1e-6f + capsule_rounding_margin(a, b, radius, box, eye_distance);
  const glm::vec3 lo = box.lo - r, hi = box.hi + r, d = b - a;
  float t0 = 0.f, t1 = 1.f;  // the part of the segment inside every slab so far
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0.f) {  // parallel to the slab: inside it or never
      if (a[k] < lo[k] || a[k] > hi[k]) return false;
      continue;
    }
    const float u = (lo[k] - a[k]) / d[k], v = (hi[k] - a[k]) / d[k];
    t0 = std::max(t0, std::min(u, v));
    t1 = std::min(t1, std::max(u, v));
  }
  return t0 <= t1;
}

// [sphere-tiles]
TileRect sphere_tiles(const FrameCamera& camera, const Grid& g, const glm::vec3& c, float radius) {
  const float r = radius * (1.f + 1e-5f) + 1e-6f;
  const float d0 = std::max(-c.z - r, 0.5f * g.znear), d1 = -c.z + r;
  if (d1 < d0) return {{0, 0}, {-1, -1}};  // wholly nearer than the near plane
  // x / d over the sphere's box is extreme at its corners.
  const glm::vec2 lo = glm::min((glm::vec2(c) - r) / d0, (glm::vec2(c) - r) / d1);
  const glm::vec2 hi = glm::max((glm::vec2(c) + r) / d0, (glm::vec2(c) + r) / d1);
  const glm::vec2 scale(camera.projection[0][0], camera.projection[1][1]), offset(camera.projection[2][0], camera.projection[2][1]);
  const glm::vec2 size(float(g.width), float(g.height)), tile(float(g.tile_w), float(g.tile_h));
  const glm::vec2 tiles(float(g.tiles_x), float(g.tiles_y));
  const glm::vec2 px_lo = ((lo * scale - offset) * 0.5f + 0.5f) * size - 1.f, px_hi = ((hi * scale - offset) * 0.5f + 0.5f) * size + 1.f;
  return {glm::ivec2(glm::clamp(glm::floor(px_lo / tile), glm::vec2(0.f), tiles)),
          glm::ivec2(glm::clamp(glm::floor(px_hi / tile), glm::vec2(-1.f), tiles - 1.f))};
}
// [/sphere-tiles]

// [depth-bits]
int depth_bin(float lo, float hi, float d) {
  const float t = (d - lo) / std::max(hi - lo, 1e-30f) * float(kDepthBins);
  return int(std::clamp(std::floor(t), 0.f, float(kDepthBins - 1)));  // clamped as a float: no overflow
}

std::uint32_t depth_range_bits(float lo, float hi, float d0, float d1) {
  const int b0 = depth_bin(lo, hi, d0), b1 = depth_bin(lo, hi, d1);
  const std::uint32_t upto_b1 = b1 == kDepthBins - 1 ? 0xFFFFFFFFu : (1u << (b1 + 1)) - 1u;
  return upto_b1 & ~((1u << b0) - 1u);
}

std::uint32_t light_depth_bits(float lo, float hi, float z, float radius) {
  const float r = radius * (1.f + 1e-5f) + 1e-6f + kDepthPad * hi;
  return depth_range_bits(lo, hi, z - r, z + r);
}
// [/depth-bits]

}  // namespace lp::ch09
