// Exercise 1 of chapter 10, solved: the same function as 10_frame/shaders/transparent.frag.
// McGuire and Bavoil's first depth weight (transparency.h's wboit_weight, its C++ twin).
float wboit_weight(float z, float alpha) {
  float a = z / 5.0, b = z / 200.0;
  return alpha * clamp(10.0 / (1e-5 + a * a + b * b * b * b * b * b), 1e-2, 3e3);
}
