// Exercise 1 of chapter 08, solved: the same function as 08_ssgi/shaders/ssgi.comp.
float disk_transfer(vec3 p, vec3 np, vec3 e, vec3 ne, float area) {
  vec3 v = e - p;
  float r2 = dot(v, v);
  if (r2 <= 0.0 || area <= 0.0) return 0.0;
  v *= inversesqrt(r2);
  return area * max(-dot(ne, v), 0.0) * max(dot(np, v), 0.0) / (PI * r2 + area);
}
