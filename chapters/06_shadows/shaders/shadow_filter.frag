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
// MSM: the four moments (z, z^2, z^3, z^4), through the optimised map when the target is 16-bit
// (MSM_OPTIMIZED; shadow_math.h [msm]: the map is affine, so filtering commutes with it).
vec4 moments_at(ivec2 p) {
  ivec2 size = textureSize(u_input, 0);
  vec4 t = texelFetch(u_input, clamp(p, ivec2(0), size - 1), 0);
  if (!u_from_depth) return t;
  float z = t.x, z2 = z * z;
  vec4 b = vec4(z, z2, z2 * z, z2 * z2);
#ifdef MSM_OPTIMIZED
  b = mat4(-2.07224649, 13.7948857237, 0.105877704, 9.7924062118,
           32.23703778, -59.4683975703, -1.9077466311, -33.7652110555,
           -68.571074599, 82.0359750338, 9.3496555107, 47.9456096605,
           39.3703274134, -35.364903257, -6.6543490743, -23.9728048165) * b;
  b.x += 0.035955884801;
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
  float l_max = -3.4e38;
  for (int i = -u_radius; i <= u_radius; ++i) l_max = max(l_max, value_at(p + i * u_step).x);
  float sum = 0.0;
  for (int i = -u_radius; i <= u_radius; ++i) sum += w * exp(value_at(p + i * u_step).x - l_max);
  out_value = vec4(l_max + log(sum), 0.0, 0.0, 1.0);
#endif
}
// [/filter-glsl]
#endif  // SHADOW_MSM
