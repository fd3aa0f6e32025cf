// A reader's answer that does not compile (tests/01_forward.cmake: the error names this file and line).
void blinn_phong(vec3 n, vec3 to_eye, vec3 to_light, vec3 radiance, float exponent, inout vec3 diffuse, inout vec3 specular) {
  this is not GLSL;
}
