// Exercise 3 of chapter 04, solved: the same function as 04_neon/shaders/neon.glsl.
float neon_closest_on_segment(vec3 p, vec3 a, vec3 b) {
  vec3 ab = b - a;
  float len2 = dot(ab, ab);
  if (len2 < 1e-20) return 0.0;
  return clamp(dot(p - a, ab) / len2, 0.0, 1.0);
}
