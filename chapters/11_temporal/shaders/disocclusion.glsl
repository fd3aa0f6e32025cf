// Was a pixel's surface hidden last frame? The test TAA's resolve and the temporal AO share
// (taa_resolve.frag, ao_accumulate.comp), on chapter 11's motion targets (motion.h).
layout(binding = 2) uniform sampler2D u_motion;           // motion.h: xy uv motion, z depth then, w depth now
layout(binding = 3) uniform sampler2D u_previous_motion;  // the last frame's (its w: the last depths)
uniform float u_depth_tolerance;
uniform float u_depth_slope;  // pixels: how far along the surface's slope the last samples may lie

// With --exercise 3 the reader's disoccluded (chapters/11_temporal/exercises/) stands in.
#ifdef EXERCISE_DISOCCLUDED
#include EXERCISE_DISOCCLUDED
#else
// [disocclusion]
// Hidden last frame: none of the four last-frame depths around where this surface was lies
// within the tolerance of the depth it had there, widened by `slack`, how far the depth runs
// along this surface between where it was and where those samples were taken.
bool disoccluded(vec2 uv_then, float depth_then, float slack) {
  vec2 size = vec2(textureSize(u_previous_motion, 0));
  ivec2 base = ivec2(floor(uv_then * size - 0.5));
  float nearest = 1e30;
  for (int j = 0; j <= 1; ++j)
    for (int i = 0; i <= 1; ++i) {
      ivec2 q = clamp(base + ivec2(i, j), ivec2(0), ivec2(size) - 1);
      nearest = min(nearest, abs(texelFetch(u_previous_motion, q, 0).w - depth_then));
    }
  return nearest > u_depth_tolerance * depth_then + slack;
}
// [/disocclusion]
#endif

// [depth-slope]
// A grazing surface's depth changes fast from pixel to pixel. The last frame's samples nearest
// where this surface was lie up to 1.5 pixels from it on each axis (half a texel to the
// nearest of the footprint, and the two frames' jitters less than a pixel apart), so their
// depths may differ from its own by u_depth_slope (1.5) times its change per pixel on each
// axis. The change is the smaller one-sided difference of this frame's depths then, so a
// neighbour across an edge does not widen the test.
float depth_slack(ivec2 p, ivec2 size, float depth_then) {
  float l = texelFetch(u_motion, clamp(p - ivec2(1, 0), ivec2(0), size - 1), 0).z;
  float r = texelFetch(u_motion, clamp(p + ivec2(1, 0), ivec2(0), size - 1), 0).z;
  float d = texelFetch(u_motion, clamp(p - ivec2(0, 1), ivec2(0), size - 1), 0).z;
  float u = texelFetch(u_motion, clamp(p + ivec2(0, 1), ivec2(0), size - 1), 0).z;
  float dx = min(abs(r - depth_then), abs(depth_then - l));
  float dy = min(abs(u - depth_then), abs(depth_then - d));
  return u_depth_slope * (dx + dy);
}
// [/depth-slope]
