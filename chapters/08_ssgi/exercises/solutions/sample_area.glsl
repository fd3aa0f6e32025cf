// Exercise 3 of chapter 08, solved: the same function as 08_ssgi/shaders/ssgi.comp.
float sample_area(float share, float zr, vec3 e, vec3 ne) {
  float ze = view_depth(e);
  return share * (ze / zr) * (ze / zr) / max(abs(dot(ne, normalize(gb_eye.xyz - e))), 0.2);
}
