#version 450
// Temporal AO, one pixel: this frame's AO (chapter 07's, few samples, its noise turned this
// frame) blended into the history moved by the motion vectors. The history is read from the
// four texels around where the surface was, each only if its depth is this surface's, and
// dropped where none is (disoccluded: the test TAA's resolve uses; history.glsl).
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 1) uniform sampler2D u_history;  // RG32F: x AO, y frames in it
#include "11_temporal/shaders/disocclusion.glsl"
#include "11_temporal/shaders/history.glsl"
layout(r32f, binding = 0) uniform image2D u_ao;              // in: this frame's AO; out: the accumulated
layout(rg32f, binding = 1) writeonly uniform image2D u_out;  // the next history
uniform int u_reset;
uniform float u_max_frames;

// [ao-accumulate]
void main() {
  ivec2 size = imageSize(u_ao);
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, size))) return;
  float a = imageLoad(u_ao, p).r;
  vec4 own = texelFetch(u_motion, p, 0);
  vec2 uv_then;
  float slack;
  vec2 result = vec2(a, 1.0);
  if (!history_lost(p, size, own, u_reset != 0, uv_then, slack)) {
    ivec2 q[4];
    float w[4];
    float weights = history_footprint(uv_then, size, own.z, slack, q, w);
    vec2 h = vec2(0.0);
    for (int k = 0; k < 4; ++k) h += w[k] * texelFetch(u_history, q[k], 0).rg;
    if (weights > 0.0) {
      h /= weights;
      float n = min(h.y + 1.0, u_max_frames);  // this frame weighs 1 / n: the running mean, then a fixed share
      result = vec2(mix(h.x, a, 1.0 / n), n);
    }
  }
  imageStore(u_ao, p, vec4(result.x, 0.0, 0.0, 0.0));
  imageStore(u_out, p, vec4(result, 0.0, 0.0));
}
// [/ao-accumulate]
