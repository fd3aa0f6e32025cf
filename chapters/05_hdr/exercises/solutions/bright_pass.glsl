// Exercise 3 of chapter 05, solved: the same function as 05_hdr/shaders/hdr_math.glsl.
vec3 bright_pass(vec3 x, float threshold, float limit) {
  float y = luminance(x);
  if (y <= threshold || y <= 0.0) return vec3(0.0);
  return x * (min(y - threshold, limit) / y);
}
