#version 450
// Temporal AO, one pixel: this frame's AO (chapter 07's, few samples, its noise turned this
// frame) blended into the history moved by the motion vectors. The history is read from the
// four texels around where the surface was, each only if its depth is this surface's (a
// bilinear read across an edge would bring in the other surface's AO), and dropped where
// none is (disoccluded: the test TAA's resolve uses).
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 1) uniform sampler2D u_history;  // RG32F: x AO, y frames in it
#include "11_temporal/shaders/disocclusion.glsl"
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
  vec2 uv_then = (vec2(p) + 0.5) / vec2(size) - own.xy;
  bool rejected = u_reset != 0 || any(lessThan(uv_then, vec2(0.0))) || any(greaterThan(uv_then, vec2(1.0)));
  float slack = depth_slack(p, size, own.z);
  if (!rejected) rejected = disoccluded(uv_then, own.z, slack);
  vec2 result = vec2(a, 1.0);
  if (!rejected) {
    // The bilinear footprint, each texel weighed by its bilinear weight if it is this surface.
    vec2 pos = uv_then * vec2(size) - 0.5;
    ivec2 base = ivec2(floor(pos));
    vec2 f = pos - vec2(base);
    vec2 h = vec2(0.0);
    float weights = 0.0;
    for (int j = 0; j <= 1; ++j)
      for (int i = 0; i <= 1; ++i) {
        ivec2 q = clamp(base + ivec2(i, j), ivec2(0), size - 1);
        float w = (i == 1 ? f.x : 1.0 - f.x) * (j == 1 ? f.y : 1.0 - f.y);
        bool same = abs(texelFetch(u_previous_motion, q, 0).w - own.z) <= u_depth_tolerance * own.z + slack;
        if (same && w > 0.0) {
          h += w * texelFetch(u_history, q, 0).rg;
          weights += w;
        }
      }
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
