#version 450
// One small addend per pixel for the half-float blending test (test_03_light_volumes_gl.cpp):
// (64 + x) / 2^14 at column x, exact in half and in float, so only the blend's rounding of the
// sum is measured.
layout(location = 0) out vec4 o_colour;
void main() {
  const float v = (64.0 + floor(gl_FragCoord.x)) / 16384.0;
  o_colour = vec4(v, v, v, v);
}
