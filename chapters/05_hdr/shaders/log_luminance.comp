#version 450
// Level 0 of the log-luminance mip chain: for every pixel, R = log(delta + L) and G = 1,
// the number of pixels it stands for. With the chapter's policy (default) a NaN pixel gets
// G = 0, so no level above counts it; with RAW (the naive chain, the source as written)
// every value goes in as it is, NaN and Inf included.
#include "05_hdr/shaders/hdr_math.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D u_radiance;
layout(rg32f, binding = 0) writeonly uniform image2D u_level0;
uniform float u_delta;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(u_level0)))) return;
  vec3 c = texelFetch(u_radiance, p, 0).rgb;
  // [log-pass]
#ifdef RAW
  imageStore(u_level0, p, vec4(log(u_delta + luminance(c)), 1.0, 0.0, 0.0));
#else
  bool valid;
  vec3 s = sanitize(c, valid);
  imageStore(u_level0, p, valid ? vec4(log_luminance(s, u_delta), 1.0, 0.0, 0.0) : vec4(0.0));
#endif
  // [/log-pass]
}
