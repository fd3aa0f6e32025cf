// Exercise 2 of chapter 04, solved: the same function as 04_neon/shaders/neon.glsl.
float neon_analytic_diffuse(NeonSurface s, Neon t) {
  if (t.len < NEON_MIN_LENGTH) return neon_point_light_terms(s, t).x;
  NeonFrame f = neon_frame(s.position, t, s.normal);
  float s0, s1;
  if (!neon_clip_to_horizon(f, s.normal, s0, s1)) return 0.0;
  float d = f.d, r0 = sqrt(d * d + s0 * s0), r1 = sqrt(d * d + s1 * s1);
  float span = s1 - s0, sum = s0 + s1;
  float dsin = s0 * s1 <= 0.0 ? s1 / r1 - s0 / r0 : d * d * span * sum / (r0 * r1 * (s1 * r0 + s0 * r1));
  float dcos = d * span * sum / (r0 * r1 * (r0 + r1));
  float nw = dot(s.normal, f.w), nu = dot(s.normal, f.u);
  return max(0.0, (nw * dsin + nu * dcos) / (t.len * d));
}
