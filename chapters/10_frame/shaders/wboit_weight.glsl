// The weighted blended pass's weight, in a file of its own so that a test can run it against
// its C++ twin (tests/unit/test_10_twins_gl.cpp); transparent.frag includes it.
// [wboit-weight-glsl]
// McGuire and Bavoil's first depth weight (transparency.h's wboit_weight, its C++ twin).
float wboit_weight(float z, float alpha) {
  float a = z / 5.0, b = z / 200.0;
  return alpha * clamp(10.0 / (1e-5 + a * a + b * b * b * b * b * b), 1e-2, 3e3);
}
// [/wboit-weight-glsl]
