// Exercise 2 of chapter 11, solved: the same function as 11_temporal/shaders/taa_resolve.frag.
vec3 clip_to_box(vec3 lo, vec3 hi, vec3 q) {
  vec3 c = 0.5 * (hi + lo), e = 0.5 * (hi - lo);
  vec3 v = q - c;
  vec3 a = abs(v / e);
  float m = max(a.x, max(a.y, a.z));
  return m > 1.0 ? c + v / m : q;
}
