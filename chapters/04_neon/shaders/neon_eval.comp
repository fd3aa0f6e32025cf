#version 450
// Evaluates neon_light() for a list of (surface, tube, method) cases, so a test can hold the
// GLSL to the C++ of neon.cpp case by case.
#include "04_neon/shaders/neon.glsl"

layout(local_size_x = 64) in;

struct Case {
  vec4 position_exponent;  // xyz: position, w: Blinn-Phong exponent
  vec4 normal;             // xyz
  vec4 to_eye;             // xyz
  ivec4 method;            // x: NEON_*, y: samples, z: tube index
};

layout(std430, binding = 0) readonly buffer Cases { Case cases[]; };
layout(std430, binding = 1) readonly buffer Tubes { NeonGpu tubes[]; };
layout(std430, binding = 2) writeonly buffer Results { vec4 results[]; };  // diffuse.rgb, spec.r; 2 per case

uniform int u_count;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(u_count)) return;
  Case c = cases[i];
  NeonSurface s = NeonSurface(c.position_exponent.xyz, c.normal.xyz, c.to_eye.xyz, c.position_exponent.w);
  NeonResult r = neon_light(s, tubes[c.method.z], NeonMethod(c.method.x, c.method.y));
  results[2 * i] = vec4(r.diffuse, 0.0);
  results[2 * i + 1] = vec4(r.specular, 0.0);
}
