#version 450
// The bilateral blur of the randomised pattern's noise, indirect light and AO together: a 5x5
// box whose neighbours count only when they are the same surface, with chapter 07's test
// (ao_math.h's bilateral_weight: view depth within u_depth_threshold of the centre's,
// relative, normal within acos(u_normal_threshold)). The sky is never averaged in. Chapter
// 07's blur is one channel and 4x4 (its noise tile's size); this noise has no tile. With
// u_keep_transfer (chapter 11) it averages the transfer too, and the light before the clamp:
// the light times max(transfer, 1), clamped again by the averaged transfer.
layout(local_size_x = 8, local_size_y = 8) in;
#include "02_gbuffer/shaders/gbuffer.glsl"
#include "07_ssao/shaders/ao_math.glsl"

layout(rgba16f, binding = 0) uniform readonly image2D u_raw;
layout(rgba16f, binding = 1) uniform writeonly image2D u_out;
uniform mat4 u_view;
uniform float u_depth_threshold, u_normal_threshold;
layout(r32f, binding = 2) uniform readonly image2D u_raw_transfer;
layout(r32f, binding = 3) uniform writeonly image2D u_out_transfer;
uniform int u_keep_transfer;

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(u_out);
  if (any(greaterThanEqual(q, size))) return;
  Surface c = decode_gbuffer(q);
  bool keep = u_keep_transfer != 0;
  if (c.is_sky) {
    imageStore(u_out, q, imageLoad(u_raw, q));
    if (keep) imageStore(u_out_transfer, q, imageLoad(u_raw_transfer, q));
    return;
  }
  float zc = -(u_view * vec4(c.position, 1.0)).z;
  vec4 sum = vec4(0.0);
  float weight = 0.0, transfer = 0.0;
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx) {
      ivec2 n = clamp(q + ivec2(dx, dy), ivec2(0), size - 1);
      float depth = texelFetch(gb_depth, n, 0).r;
      if (depth == gb_depth_info.z) continue;
      float z = -(u_view * vec4(reconstruct_position(vec2(n) + 0.5, depth), 1.0)).z;
      vec3 nn = decode_normal(texelFetch(gb_normal, n, 0));
      float w = bilateral_weight(zc, z, c.normal, nn, u_depth_threshold, u_normal_threshold);  // chapter 07's
      vec4 v = imageLoad(u_raw, n);
      if (keep) {
        float t = imageLoad(u_raw_transfer, n).r;
        v.rgb *= max(t, 1.0);
        transfer += w * t;
      }
      sum += w * v;
      weight += w;
    }
  if (!keep) {
    imageStore(u_out, q, weight > 0.0 ? sum / weight : imageLoad(u_raw, q));
    return;
  }
  if (weight > 0.0) {
    sum /= weight;
    transfer /= weight;
    sum.rgb /= max(transfer, 1.0);
    imageStore(u_out, q, sum);
    imageStore(u_out_transfer, q, vec4(transfer, 0.0, 0.0, 0.0));
  } else {
    imageStore(u_out, q, imageLoad(u_raw, q));
    imageStore(u_out_transfer, q, imageLoad(u_raw_transfer, q));
  }
}
