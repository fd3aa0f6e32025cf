// A plausible wrong answer to chapter 06's exercise 2 (tests/06_shadows.cmake: it must fail):
// P_min subtracted without rescaling what is left to [0, 1], so the penumbrae are too dark.
float vsm_visibility(vec2 m, float d) {
  if (d <= m.x) return 1.0;
  float variance = max(m.y - m.x * m.x, sh.min_variance);
  float t = d - m.x;
  float p_max = variance / (variance + t * t);
  return clamp(p_max - sh.vsm_p_min, 0.0, 1.0);
}
