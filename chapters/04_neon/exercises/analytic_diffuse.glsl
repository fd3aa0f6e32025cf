// Exercise 2 of chapter 04: the exact diffuse light of a line.
// `./run 04 --exercise 2` lights with this function (the default mode uses it, and
// `--mode analytic-diffuse` shows it alone); add `--check` to compare.
//
// A tube shorter than NEON_MIN_LENGTH is a point light: return neon_point_light_terms(s, t).x.
// Otherwise, in the tube's frame seen from the point (neon_frame(s.position, t, s.normal):
// the line is P(x) - position = d w + x u), clip the tube to the surface's horizon
// (neon_clip_to_horizon(f, s.normal, s0, s1); nothing visible: return 0). With
// d = f.d, r0 = sqrt(d^2 + s0^2) and r1 = sqrt(d^2 + s1^2), the tube's unit intensity spread
// over its length t.len gives
//     max(0, (n.w (s1/r1 - s0/r0) + n.u (d/r0 - d/r1)) / (t.len d))
// with n = s.normal, w = f.w, u = f.u. (The chapter's solution writes the two differences in
// forms that lose no precision when s0 and s1 are close; see the book.)
float neon_analytic_diffuse(NeonSurface s, Neon t) {
  return 0.0;  // no diffuse light from the tube: write the integral
}
