#version 450
// The shading floor's lists (zbin-floor, a benchmark): for each pixel, exactly the lights
// whose cut reaches its surface, found from Z-binning's lists and stored compacted, so that
// the shading pass after it does the per-pair arithmetic and nothing else. Bounded as the
// index list is: a pixel whose list does not fit is counted and shaded through Z-binning.
layout(local_size_x = 8, local_size_y = 8) in;
#define FRAME_PIXEL_COMPUTE 1  // shade.glsl's hooks read this invocation's pixel
#include "09_clustered/shaders/shade.glsl"

layout(std430, binding = 5) buffer ListState {
  uint head, capacity, cells_over, over_lo, over_hi, needed_lo, needed_hi, max_count;
} state;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, u_grid.xy))) return;
  uint cell = uint(pixel.y * u_grid.x + pixel.x);
  Surface s = decode_gbuffer(pixel);
  vec3 diffuse = vec3(0.0), specular = vec3(0.0);
  uint n = 0u, evaluated = 0u, lit = 0u;
  vec3 to_eye = vec3(0.0);  // (counting and writing lists light nothing)
  if (!s.is_sky) zbin_visit(s, to_eye, pixel, kZCount, n, diffuse, specular, evaluated, lit);
  cells[cell] = uvec2(0u);
  if (n == 0u) return;
  if (atomicAdd(state.needed_lo, n) > 0xFFFFFFFFu - n) atomicAdd(state.needed_hi, 1u);
  atomicMax(state.max_count, n);
  bool stored = false;
  uint at = 0u;
  if (atomicAdd(state.head, 0u) <= state.capacity) {
    at = atomicAdd(state.head, n);
    stored = at <= state.capacity && n <= state.capacity - at;
  }
  if (!stored) {
    atomicAdd(state.cells_over, 1u);
    if (atomicAdd(state.over_lo, n) > 0xFFFFFFFFu - n) atomicAdd(state.over_hi, 1u);
    cells[cell] = uvec2(kEveryLight, 0u);
    return;
  }
  cells[cell] = uvec2(at, n);
  zbin_visit(s, to_eye, pixel, kZWrite, at, diffuse, specular, evaluated, lit);
}
