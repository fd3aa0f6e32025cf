// The filtered maps' lookups in GLSL: the twins of shadow_math.h's chebyshev_upper_bound with
// reduce_light_bleeding (VSM) and esm_visibility_log (ESM), whose comments derive them; included
// by the lookup (shadow_visibility.glsl) and held to the C++ by
// 06_shadows.gl.GlslTwins.VsmWithPminMatchesItsCppTwin and EsmLookupMatchesItsCppTwin.

// [vsm-glsl]
// m: the filtered (E[z], E[z^2]); z: the receiver's depth.
float vsm_lit_fraction(vec2 m, float z, float min_variance, float p_min) {
  if (z <= m.x) return 1.0;
  float variance = max(m.y - m.x * m.x, min_variance);
  float d = z - m.x;
  float p_max = variance / (variance + d * d);
  return clamp((p_max - p_min) / (1.0 - p_min), 0.0, 1.0);
}
// [/vsm-glsl]

// [esm-glsl]
// l: the log of the filtered exp(c z); z: the receiver's depth.
float esm_lit_fraction(float l, float c, float z) {
  return clamp(exp(min(l - c * z, 0.0)), 0.0, 1.0);
}
// [/esm-glsl]
