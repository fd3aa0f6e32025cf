#version 450
// Chapter 08's addition (add_indirect.glsl) as a full-screen fragment pass, blended one plus
// one into chapter 03's light buffer.
#include "08_ssgi/shaders/add_indirect.glsl"

layout(location = 0) out vec4 out_diffuse;
layout(location = 1) out vec4 out_specular;

void main() {
  out_diffuse = vec4(indirect_diffuse(ivec2(gl_FragCoord.xy)), 0.0);
  out_specular = vec4(0.0);
}
