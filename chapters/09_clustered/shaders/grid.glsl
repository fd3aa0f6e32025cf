// The cells lights are binned into, in GLSL: the twin of cluster_grid.h (its comments say
// why each line is what it is). Needs the uniforms below set by ClusteredLights.
uniform mat4 u_view;         // world to view space (the G-buffer's camera)
uniform vec4 u_projection;   // P[0][0], P[1][1], P[2][0], P[2][1]: the frustum's shape
uniform ivec4 u_grid;        // width, height, tile_w, tile_h (pixels)
uniform ivec4 u_tiles;       // tiles_x, tiles_y, slices, local lights
uniform vec2 u_depth_range;  // znear, zfar (positive view depths)

const float kDepthPad = 1e-4;

float view_depth(vec3 world) { return -(u_view * vec4(world, 1.0)).z; }

#ifdef NEAR_SLICE
// A near slice (cluster_grid.h): slice 0 spans znear .. u_near_slice, the others are
// exponential from there to zfar.
uniform float u_near_slice;
#endif

float slice_start(int k) {
#ifdef NEAR_SLICE
  if (k <= 0) return u_depth_range.x;
  if (k >= u_tiles.z) return u_depth_range.y;
  return u_near_slice * pow(u_depth_range.y / u_near_slice, float(k - 1) / float(u_tiles.z - 1));
#endif
  if (k <= 0) return u_depth_range.x;
  if (k >= u_tiles.z) return u_depth_range.y;
  return u_depth_range.x * pow(u_depth_range.y / u_depth_range.x, float(k) / float(u_tiles.z));
}

// With --exercise 1 the reader's slice_of stands in (2: cell_box, 3: sphere_meets_box; their
// files are in chapters/09_clustered/exercises/).
#ifdef EXERCISE_SLICE_OF
#include EXERCISE_SLICE_OF
#else
int slice_of(float d) {
#ifdef NEAR_SLICE
  if (d < u_near_slice) return 0;
  float n = log(d / u_near_slice) / log(u_depth_range.y / u_near_slice);
  return clamp(1 + int(floor(n * float(u_tiles.z - 1))), 1, u_tiles.z - 1);
#endif
  float t = log(max(d, u_depth_range.x) / u_depth_range.x) / log(u_depth_range.y / u_depth_range.x);
  return clamp(int(floor(t * float(u_tiles.z))), 0, u_tiles.z - 1);
}
#endif

struct Box {
  vec3 lo, hi;
};

#ifdef EXERCISE_CELL_BOX
#include EXERCISE_CELL_BOX
#else
Box cell_box(ivec2 p0, ivec2 p1, float d0, float d1) {
  d0 *= 1.0 - kDepthPad;
  d1 *= 1.0 + kDepthPad;
  Box b = Box(vec3(1e30), vec3(-1e30));
  for (int i = 0; i < 8; ++i) {
    float d = (i & 1) != 0 ? d1 : d0;
    vec2 pixel = vec2((i & 2) != 0 ? p1.x : p0.x, (i & 4) != 0 ? p1.y : p0.y);
    vec2 ndc = pixel / vec2(u_grid.xy) * 2.0 - 1.0;
    vec3 v = vec3(d * (ndc.x + u_projection.z) / u_projection.x, d * (ndc.y + u_projection.w) / u_projection.y, -d);
    b.lo = min(b.lo, v);
    b.hi = max(b.hi, v);
  }
  return b;
}
#endif

#ifdef EXERCISE_SPHERE_BOX
#include EXERCISE_SPHERE_BOX
#else
bool sphere_meets_box(vec3 centre, float radius, Box box) {
  vec3 d = centre - clamp(centre, box.lo, box.hi);
  float r = radius * (1.0 + 1e-5) + 1e-6;
  return dot(d, d) <= r * r;
}
#endif

// A tube's capsule (segment a-b in view space, radius) against a box: cluster_grid.h's
// capsule_meets_box, the segment clipped against the box grown by the radius and by the margin
// that float rounding needs (capsule_rounding_margin: 64 units of roundoff of the largest size).
const float kCapsuleRoundingUlps = 64.0;
float capsule_rounding_margin(vec3 a, vec3 b, float radius, Box box, float eye_distance) {
  vec3 m = max(max(abs(a), abs(b)), max(abs(box.lo), abs(box.hi)));
  return kCapsuleRoundingUlps * exp2(-24.0) * (max(m.x, max(m.y, m.z)) + radius + eye_distance);
}
bool capsule_meets_box(vec3 a, vec3 b, float radius, Box box, float eye_distance) {
  float grow = radius * (1.0 + 1e-5) + 1e-6 + capsule_rounding_margin(a, b, radius, box, eye_distance);
  vec3 lo = box.lo - grow, hi = box.hi + grow, d = b - a;
  float t0 = 0.0, t1 = 1.0;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0.0) {
      if (a[k] < lo[k] || a[k] > hi[k]) return false;
      continue;
    }
    float u = (lo[k] - a[k]) / d[k], v = (hi[k] - a[k]) / d[k];
    t0 = max(t0, min(u, v));
    t1 = min(t1, max(u, v));
  }
  return t0 <= t1;
}

// Harada's 2.5D depth mask (cluster_grid.h's depth_bin / depth_range_bits / light_depth_bits).
const int kDepthBins = 32;
int depth_bin(float lo, float hi, float d) {
  float t = (d - lo) / max(hi - lo, 1e-30) * float(kDepthBins);
  return int(clamp(floor(t), 0.0, float(kDepthBins - 1)));
}
uint depth_range_bits(float lo, float hi, float d0, float d1) {
  int b0 = depth_bin(lo, hi, d0), b1 = depth_bin(lo, hi, d1);
  uint upto_b1 = b1 == kDepthBins - 1 ? 0xFFFFFFFFu : (1u << uint(b1 + 1)) - 1u;
  return upto_b1 & ~((1u << uint(b0)) - 1u);
}
uint light_depth_bits(float lo, float hi, float z, float radius) {
  float r = radius * (1.0 + 1e-5) + 1e-6 + kDepthPad * hi;
  return depth_range_bits(lo, hi, z - r, z + r);
}
// Tiled: per tile (min, max) view depth, and with the 2.5D mask the tile's 32 bins.
#ifdef DEPTH_MASK
const int kTileBounds = 3;
#else
const int kTileBounds = 2;
#endif

ivec2 tile_of(ivec2 pixel) { return pixel / u_grid.zw; }
// Cells in the order the assignment dispatches them: x fastest, then y, then the slice.
int cell_index(ivec2 tile, int slice) { return (slice * u_tiles.y + tile.y) * u_tiles.x + tile.x; }

// The lights, in chapter 03's light order (points, cones, wide spots), from chapter 03's
// packing (light_instances.h) with what shading a pair needs precomputed; the spots' cones
// apart, from light u_first_spot on; then chapter 04's tubes, from u_first_tube on.
#include "09_clustered/shaders/cluster_light.h"
layout(std430, binding = 0) readonly buffer Lights { ClusterLight cluster_lights[]; };
layout(std430, binding = 9) readonly buffer Spots { ClusterSpot cluster_spots[]; };
uniform int u_first_spot;  // the first spot of the light order (the lights before it are points)
uniform int u_first_tube;  // the first tube (the lights' count when there are none)
// Light i's cone: a spot's, zero for a point (and a tube, which has none).
vec4 cone_of(int i) {
  return i >= u_first_spot && i < u_first_tube ? cluster_spots[i - u_first_spot].axis_offset : vec4(0.0);
}
// Each cell's list: where it starts in the index list and how many lights it holds.
layout(std430, binding = 1) buffer Cells { uvec2 cells[]; };
layout(std430, binding = 4) buffer Indices { uint light_indices[]; };
// A cell whose list did not fit in the index list: (kEveryLight, lights), shaded from every
// light until the list grows (a frame later: ClusteredLights reads the overflow late).
const uint kEveryLight = 0xFFFFFFFFu;
