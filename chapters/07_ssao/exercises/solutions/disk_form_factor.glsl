// Exercise 3 of chapter 07, solved: the same function as 07_ssao/shaders/ao_math.glsl.
float form_factor_occlusion(vec3 p, vec3 np, vec3 e, vec3 ne, float area) {
  vec3 v = e - p;
  float d2 = dot(v, v);
  if (d2 <= 0.0 || area <= 0.0) return 0.0;
  v *= inversesqrt(d2);
  return area * abs(dot(ne, v)) * max(dot(np, v), 0.0) / (PI * d2 + area);
}
