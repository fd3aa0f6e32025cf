// Exercise 2 of chapter 09, solved: the same function as 09_clustered/shaders/grid.glsl.
Box cell_box(ivec2 p0, ivec2 p1, float d0, float d1) {
  d0 *= 1.0 - kDepthPad;
  d1 *= 1.0 + kDepthPad;
  Box b = Box(vec3(1e30), vec3(-1e30));
  for (int i = 0; i < 8; ++i) {
    float d = (i & 1) != 0 ? d1 : d0;
    vec2 pixel = vec2((i & 2) != 0 ? p1.x : p0.x, (i & 4) != 0 ? p1.y : p0.y);
    vec2 ndc = pixel / vec2(u_grid.xy) * 2.0 - 1.0;
    vec3 v = vec3(d * (ndc.x + u_projection.z) / u_projection.x, d * (ndc.y + u_projection.w) / u_projection.y, -d);
    b.lo = min(b.lo, v);
    b.hi = max(b.hi, v);
  }
  return b;
}
