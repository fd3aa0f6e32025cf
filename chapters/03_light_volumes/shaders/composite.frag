#version 450
// The final image (composite.glsl), a full-screen pass into the bound framebuffer.
#include "03_light_volumes/shaders/composite.glsl"

out vec4 out_color;

void main() { out_color = vec4(composite_colour(ivec2(gl_FragCoord.xy)), 1.0); }
