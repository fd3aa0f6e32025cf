#version 450
// The filtered maps' pre-filter, one direction per pass (a box of 2 r + 1 texels, separable:
// 2 (2 r + 1) taps per texel instead of (2 r + 1)^2). The first pass reads the depth map and
// turns each depth into what the method filters; the second reads the first's output.
//   SHADOW_VSM: the moments (z, z^2), averaged (chapter06 shadow_math.h [chebyshev])
//   SHADOW_ESM: l = c z, filtered in log space with log-sum-exp ([esm]): no exp(c z) is
//               ever formed, so nothing overflows for any c.
layout(binding = 0) uniform sampler2D u_input;
uniform ivec2 u_step;   // (1, 0) or (0, 1)
uniform int u_radius;
uniform float u_c;      // ESM's exponent
uniform bool u_from_depth;
layout(location = 0) out vec4 out_value;

#ifdef SHADOW_MSM
#include "06_shadows/shaders/msm_math.glsl"
// MSM: the four moments (z, z^2, z^3, z^4), through the optimised map when the target is 16-bit
// (MSM_OPTIMIZED; shadow_math.h [msm]: the map is affine, so filtering commutes with it).
vec4 moments_at(ivec2 p) {
  ivec2 size = textureSize(u_input, 0);
  vec4 t = texelFetch(u_input, clamp(p, ivec2(0), size - 1), 0);
  if (!u_from_depth) return t;
  vec4 b = msm_moments(t.x);
#ifdef MSM_OPTIMIZED
  b = msm_optimize(b);
#endif
  return b;
}
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float w = 1.0 / float(2 * u_radius + 1);
  vec4 sum = vec4(0.0);
  for (int i = -u_radius; i <= u_radius; ++i) sum += w * moments_at(p + i * u_step);
  out_value = sum;
}
#else
#include "06_shadows/shaders/filtered_math.glsl"

vec2 value_at(ivec2 p) {
  ivec2 size = textureSize(u_input, 0);
  p = clamp(p, ivec2(0), size - 1);
  vec4 t = texelFetch(u_input, p, 0);
  if (!u_from_depth) return t.xy;
#ifdef SHADOW_VSM
  return vec2(t.x, t.x * t.x);
#else
  return vec2(u_c * t.x, 0.0);
#endif
}

// [filter-glsl]
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float w = 1.0 / float(2 * u_radius + 1);
#ifdef SHADOW_VSM
  vec2 sum = vec2(0.0);
  for (int i = -u_radius; i <= u_radius; ++i) sum += w * value_at(p + i * u_step);
  out_value = vec4(sum, 0.0, 1.0);
#else
  // log-sum-exp about the largest value (filtered_math.glsl, shadow_math.h's esm_filter_log)
  float l_max = -3.4e38;
  for (int i = -u_radius; i <= u_radius; ++i) l_max = max(l_max, value_at(p + i * u_step).x);
  float sum = 0.0;
  for (int i = -u_radius; i <= u_radius; ++i) sum += esm_log_sum_term(value_at(p + i * u_step).x, l_max, w);
  out_value = vec4(esm_log_sum(l_max, sum), 0.0, 0.0, 1.0);
#endif
}
// [/filter-glsl]
#endif  // SHADOW_MSM
