// Exercise 2 of chapter 06, solved: the same lines as 06_shadows/shaders/shadow_visibility.glsl's [vsm-glsl].
float vsm_visibility(vec2 m, float d) {
  if (d <= m.x) return 1.0;
  float variance = max(m.y - m.x * m.x, sh.min_variance);
  float t = d - m.x;
  float p_max = variance / (variance + t * t);
  return clamp((p_max - sh.vsm_p_min) / (1.0 - sh.vsm_p_min), 0.0, 1.0);
}
