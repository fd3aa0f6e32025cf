#version 450
// Test support (tests/unit/test_02_gbuffer_gl.cpp): the GLSL encoders over the whole sphere.
// Pixel (x, y) of an odd-sized target is the octahedral point (x, y) / (size - 1) * 2 - 1, so
// the grid hits the centre (+z), the corners (-z), the edges and diagonals (the folds)
// exactly. Writes the encoded normal (to the format under test) and the direction (float).
#include "02_gbuffer/shaders/encoding.glsl"

uniform int u_bits;  // octahedral bits per axis; 0: the source's xyz
uniform vec2 u_size;
layout(location = 0) out vec4 out_code;
layout(location = 1) out vec4 out_direction;

void main() {
  vec2 p = floor(gl_FragCoord.xy) / (u_size - 1.0) * 2.0 - 1.0;
  vec3 n = octahedral_unfold(p);
  out_direction = vec4(n, 0.0);
  out_code = u_bits == 0 ? vec4(encode_xyz(n), 1.0) : vec4(encode_octahedral(n, u_bits), 0.0, 1.0);
}
