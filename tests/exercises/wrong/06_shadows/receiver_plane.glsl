// A plausible wrong answer to chapter 06's exercise 3 (tests/06_shadows.cmake: it must fail):
// the slope in metres per metre, not scaled from the map's box to its (u, v) and window depth.
vec2 receiver_plane_gradient(Surface s) {
  vec3 n = mat3(sh.view) * s.normal;
  return vec2(n.x, n.y) / max(n.z, 0.05);
}
