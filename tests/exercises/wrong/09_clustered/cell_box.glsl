// A plausible wrong answer to chapter 09's exercise 2 (tests/09_clustered.cmake: it must fail):
// the corners' x and y not scaled by their depth, as if every corner lay at a depth of 1.
Box cell_box(ivec2 p0, ivec2 p1, float d0, float d1) {
  Box b = Box(vec3(1e30), vec3(-1e30));
  for (int i = 0; i < 8; ++i) {
    float d = (i & 1) != 0 ? d1 : d0;
    vec2 pixel = vec2((i & 2) != 0 ? p1.x : p0.x, (i & 4) != 0 ? p1.y : p0.y);
    vec2 ndc = pixel / vec2(u_grid.xy) * 2.0 - 1.0;
    vec3 v = vec3((ndc.x + u_projection.z) / u_projection.x, (ndc.y + u_projection.w) / u_projection.y, -d);
    b.lo = min(b.lo, v);
    b.hi = max(b.hi, v);
  }
  return b;
}
