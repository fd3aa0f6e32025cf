#version 450
// Evaluates light_incident() and blinn_phong() of lighting.glsl for a list of cases, so a test
// can hold the GLSL to its C++ twin (blinn_phong.h) case by case: tests/unit/test_forward_gl.cpp.
#include "01_forward/shaders/lighting.glsl"

layout(local_size_x = 64) in;

struct Case {
  vec4 position_exponent;  // xyz: surface position, w: Blinn-Phong exponent
  vec4 normal;             // xyz (not necessarily unit length: the hard cases)
  vec4 to_eye;             // xyz
};

layout(std430, binding = 0) readonly buffer Cases { Case cases[]; };
layout(std430, binding = 1) readonly buffer Lights { GpuLight lights[]; };  // one per case
layout(std430, binding = 2) writeonly buffer Results { vec4 results[]; };  // diffuse, specular: 2 per case

uniform int u_count;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(u_count)) return;
  Case c = cases[i];
  vec3 to_light, radiance;
  light_incident(lights[i], c.position_exponent.xyz, to_light, radiance);
  vec3 diffuse = vec3(0.0), specular = vec3(0.0);
  blinn_phong(c.normal.xyz, c.to_eye.xyz, to_light, radiance, c.position_exponent.w, diffuse, specular);
  results[2 * i] = vec4(diffuse, 0.0);
  results[2 * i + 1] = vec4(specular, 0.0);
}
