// Exercise 3 of chapter 09, solved: the same function as 09_clustered/shaders/grid.glsl.
bool sphere_meets_box(vec3 centre, float radius, Box box) {
  vec3 d = centre - clamp(centre, box.lo, box.hi);
  float r = radius * (1.0 + 1e-5) + 1e-6;
  return dot(d, d) <= r * r;
}
