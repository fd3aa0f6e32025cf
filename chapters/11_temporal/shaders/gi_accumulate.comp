#version 450
// Temporal AO and indirect light in the whole frame, one pixel: this frame's result of chapter
// 08's pass (rgb the indirect light L1_ind, a the AO's visibility A; few samples, a part of a
// larger pattern, turned this frame) blended into the history moved by the motion vectors,
// read and dropped as the AO's is (history.glsl). The pass's clamp (ssgi.comp's [ssgi-clamp])
// is applied to the accumulated sums, not to each frame's: the history holds the light before
// the clamp and the transfer total, and the output divides one by the other after the blend.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 1) uniform sampler2D u_history;         // RGBA32F: L1_ind before the clamp, and A, accumulated
layout(binding = 4) uniform sampler2D u_history_frames;  // RG32F: the frames in it, the transfer total accumulated
#include "11_temporal/shaders/disocclusion.glsl"
#include "11_temporal/shaders/history.glsl"
layout(rgba16f, binding = 0) uniform image2D u_gi;                // in: this frame's; out: the accumulated
layout(rgba32f, binding = 1) writeonly uniform image2D u_out;     // the next history
layout(rg32f, binding = 2) writeonly uniform image2D u_out_frames;
layout(r32f, binding = 3) readonly uniform image2D u_transfer;    // this frame's transfer total (Ssgi::transfer())
uniform int u_reset;
uniform float u_max_frames;

void main() {
  ivec2 size = imageSize(u_gi);
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, size))) return;
  // [gi-accumulate]
  vec4 result = imageLoad(u_gi, p);  // this frame's, clamped by its own transfer: a history starts so
  float t = imageLoad(u_transfer, p).r, n = 1.0, transfer = t;
  vec4 sums = vec4(result.rgb * max(t, 1.0), result.a);  // its light before the clamp
  vec4 own = texelFetch(u_motion, p, 0);
  vec2 uv_then;
  float slack;
  if (!history_lost(p, size, own, u_reset != 0, uv_then, slack)) {
    ivec2 q[4];
    float w[4];
    float weights = history_footprint(uv_then, size, own.z, slack, q, w);
    vec4 h = vec4(0.0);
    vec2 frames = vec2(0.0);
    for (int k = 0; k < 4; ++k) {
      h += w[k] * texelFetch(u_history, q[k], 0);
      frames += w[k] * texelFetch(u_history_frames, q[k], 0).rg;
    }
    if (weights > 0.0) {
      n = min(frames.x / weights + 1.0, u_max_frames);  // this frame weighs 1 / n, as the AO's
      sums = mix(h / weights, sums, 1.0 / n);
      transfer = mix(frames.y / weights, t, 1.0 / n);
      result = vec4(sums.rgb / max(transfer, 1.0), sums.a);  // the clamp, on the accumulated sums
    }
  }
  imageStore(u_gi, p, result);
  imageStore(u_out, p, sums);
  imageStore(u_out_frames, p, vec4(n, transfer, 0.0, 0.0));
  // [/gi-accumulate]
}
