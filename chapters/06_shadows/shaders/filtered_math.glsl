// The filtered maps in GLSL: the twins of shadow_math.h's esm_filter_log (ESM's pre-filter),
// chebyshev_upper_bound with reduce_light_bleeding (VSM) and esm_visibility_log (ESM), whose
// comments derive them; included by the pre-filter (shadow_filter.frag) and the lookup
// (shadow_visibility.glsl), and held to the C++ by 06_shadows.gl.GlslTwins.EsmFilterLogMatchesItsCppTwin,
// VsmWithPminMatchesItsCppTwin and EsmLookupMatchesItsCppTwin.

// shadow_math.h's esm_filter_log, log-sum-exp about the largest value, in the pre-filter's two
// passes over the taps: l_max, the largest l_i, then L = esm_log_sum(l_max, the sum over the
// taps of esm_log_sum_term(l_i, l_max, w_i)). Every exponent is <= 0: nothing overflows.
float esm_log_sum_term(float l, float l_max, float w) { return w * exp(l - l_max); }
float esm_log_sum(float l_max, float sum) { return l_max + log(sum); }

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
