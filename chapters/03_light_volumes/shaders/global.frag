#version 450
// The lights that reach every pixel (global_light.glsl) as a full-screen fragment pass: one
// fragment per pixel, the light buffer written through the framebuffer. global.comp is the
// same body in compute.
#include "03_light_volumes/shaders/global_light.glsl"

layout(early_fragment_tests) in;

layout(location = 0) out vec4 out_diffuse;
layout(location = 1) out vec4 out_specular;

void main() {
  vec4 l1, l2;
  global_light(ivec2(gl_FragCoord.xy), l1, l2);
  out_diffuse = l1;
#ifndef LIGHT_PREPASS
  out_specular = l2;
#endif
}
