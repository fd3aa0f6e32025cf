// Exercise 1 of chapter 02, solved: the same function as 02_gbuffer/shaders/encoding.glsl.
vec2 octahedral_fold(vec3 n) {
  vec2 p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
  if (n.z < 0.0) p = (1.0 - abs(p.yx)) * gb_sign_not_zero(p);
  return p;
}
