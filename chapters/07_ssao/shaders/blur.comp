#version 450
// The bilateral blur of the classic AO: a 4x4 box (the noise tile's size) whose neighbours
// count only when they are the same surface (ao_math.h's bilateral_weight: view depth within
// u_depth_threshold of the centre's, relative, and normal within acos(u_normal_threshold)).
// The sky is never averaged in and stays 1.
layout(local_size_x = 8, local_size_y = 8) in;
#include "02_gbuffer/shaders/gbuffer.glsl"
#include "07_ssao/shaders/ao_math.glsl"

layout(r32f, binding = 0) uniform readonly image2D u_raw;
layout(r32f, binding = 1) uniform writeonly image2D u_out;
uniform mat4 u_view;
uniform int u_scale;
uniform float u_depth_threshold, u_normal_threshold;

// [blur]
void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(u_out);
  if (any(greaterThanEqual(q, size))) return;
  ivec2 last = ivec2(gb_size.xy) - 1;
  ivec2 pixel = min(q * u_scale + u_scale / 2, last);
  Surface c = decode_gbuffer(pixel);
  if (c.is_sky) { imageStore(u_out, q, vec4(1.0)); return; }
  float zc = -(u_view * vec4(c.position, 1.0)).z;
  float sum = 0.0, weight = 0.0;
  for (int dy = -2; dy < 2; ++dy)
    for (int dx = -2; dx < 2; ++dx) {
      ivec2 n = clamp(q + ivec2(dx, dy), ivec2(0), size - 1);
      ivec2 np = min(n * u_scale + u_scale / 2, last);
      float depth = texelFetch(gb_depth, np, 0).r;
      if (depth == gb_depth_info.z) continue;  // the sky never darkens (or lightens) geometry
      vec3 pos = reconstruct_position(vec2(np) + 0.5, depth);
      float z = -(u_view * vec4(pos, 1.0)).z;
      vec3 nn = decode_normal(texelFetch(gb_normal, np, 0));
      float w = bilateral_weight(zc, z, c.normal, nn, u_depth_threshold, u_normal_threshold);  // ao_math.glsl
      sum += w * imageLoad(u_raw, n).r;
      weight += w;
    }
  imageStore(u_out, q, vec4(weight > 0.0 ? sum / weight : imageLoad(u_raw, q).r));
}
// [/blur]
