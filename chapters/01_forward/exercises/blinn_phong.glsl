// Exercise 1 of chapter 01: Blinn's half vector and the normalised specular lobe.
// `./run 01 --exercise 1` lights the scene with this function; add `--check` to compare.
//
// Lambert's diffuse term is done. Write the specular term: the half vector h between the
// directions to the light and to the eye (normalised; none when they are opposite), the lobe
// (n + 8) / 8 * max(n.h, 0)^exponent, and add radiance * lobe * n.l to `specular`.
void blinn_phong(vec3 n, vec3 to_eye, vec3 to_light, vec3 radiance, float exponent,
                 inout vec3 diffuse, inout vec3 specular) {
  float n_dot_l = dot(n, to_light);
  if (n_dot_l <= 0.0) return;
  diffuse += radiance * n_dot_l;
  // your specular term here
}
