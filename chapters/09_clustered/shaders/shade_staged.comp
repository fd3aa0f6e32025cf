#version 450
// Pass 3 in compute with the tile's lights staged in shared memory (tiled only): one work
// group per tile, one invocation per pixel. The group loads a chunk of its tile's list, one
// record per invocation, into shared memory, then every pixel adds the whole chunk from
// there: each record is read from memory once per tile instead of once per pixel. The same
// lights in the same order through the same add_record() as shade.comp.
layout(local_size_x = STAGE_TILE, local_size_y = STAGE_TILE) in;
#define FRAME_PIXEL_COMPUTE 1  // the frame's hooks read this invocation's pixel
#include "09_clustered/shaders/shade.glsl"

layout(binding = LIGHT_BUFFER_IMAGE + 0, rgba16f) uniform image2D u_l1;  // LightBuffer::image_defines()
layout(binding = LIGHT_BUFFER_IMAGE + 1, rgba16f) uniform image2D u_l2;

// Records staged at once: at most 256 (13 KiB; GL promises 32 KiB of shared memory, and
// 32-pixel tiles' 1 024 invocations would need 52).
const uint kChunk = min(uint(STAGE_TILE * STAGE_TILE), 256u);
shared ClusterLight s_light[kChunk];
shared vec4 s_cone[kChunk];
shared int s_index[kChunk];

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  bool inside = all(lessThan(pixel, u_grid.xy));
  Surface s = decode_gbuffer(inside ? pixel : ivec2(0));
  bool shaded = inside && !s.is_sky;
  // The group is the tile (the grid's tiles are STAGE_TILE pixels): its list is the group's,
  // so the loop below is uniform and its barriers are reached by every invocation.
  uvec2 list = cells[cell_index(ivec2(gl_WorkGroupID.xy), 0)];
  uint t = gl_LocalInvocationIndex;
  vec3 diffuse = vec3(0.0), specular = vec3(0.0);
  vec3 to_eye = normalize(gb_eye.xyz - s.position);
  uint lit = 0u;
  // [stage]
  for (uint base = 0u; base < list.y; base += kChunk) {
    uint n = min(kChunk, list.y - base);
    if (t < n) {
      uint i = light_of(list, base + t);
      s_light[t] = cluster_lights[i];
      s_cone[t] = cone_of(int(i));
      s_index[t] = int(i);
    }
    barrier();
    if (shaded)
      for (uint k = 0u; k < n; ++k) add_record(s, to_eye, s_index[k], s_light[k], s_cone[k], diffuse, specular, lit);
    barrier();
  }
  // [/stage]
  if (!inside) return;
  uint evaluated = shaded ? list.y : 0u;
  if (shaded) count_pixel(evaluated, lit);
  vec4 l1, l2;
  output_of(diffuse, specular, evaluated, lit, l1, l2);
  imageStore(u_l1, pixel, imageLoad(u_l1, pixel) + l1);
  imageStore(u_l2, pixel, imageLoad(u_l2, pixel) + l2);
}
