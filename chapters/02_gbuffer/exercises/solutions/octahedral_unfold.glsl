// Exercise 2 of chapter 02, solved: the same function as 02_gbuffer/shaders/encoding.glsl.
vec3 octahedral_unfold(vec2 p) {
  vec3 n = vec3(p, 1.0 - abs(p.x) - abs(p.y));
  float t = max(-n.z, 0.0);
  n.x += n.x >= 0.0 ? -t : t;
  n.y += n.y >= 0.0 ? -t : t;
  return normalize(n);
}
