#version 450
// Pass 3 as a full-screen fragment pass: the same shade_pixel() as shade.comp, the sum
// added into the light buffer by additive blending.
#include "09_clustered/shaders/shade.glsl"

layout(location = 0) out vec4 out_diffuse;
layout(location = 1) out vec4 out_specular;

void main() { pixel_output(ivec2(gl_FragCoord.xy), out_diffuse, out_specular); }
