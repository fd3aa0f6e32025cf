// Exercise 1 of chapter 01, solved: the same function as 01_forward/shaders/lighting.glsl.
void blinn_phong(vec3 n, vec3 to_eye, vec3 to_light, vec3 radiance, float exponent,
                 inout vec3 diffuse, inout vec3 specular) {
  float n_dot_l = dot(n, to_light);
  if (n_dot_l <= 0.0) return;
  diffuse += radiance * n_dot_l;
  if (to_light + to_eye == vec3(0.0)) return;  // the eye opposite the light: no half vector
  vec3 h = normalize(to_light + to_eye);
  float n_dot_h = max(dot(n, h), 0.0);
  float lobe = (exponent + 8.0) / 8.0 * pow(n_dot_h, exponent);
  specular += radiance * (lobe * n_dot_l);
}
