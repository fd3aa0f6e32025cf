#version 450
// One neon term from chapter 03's light buffer, as the forward pass's --term shows it:
// albedo x L1 (1, the diffuse light) or L2 (2, the specular light). With --term the light
// buffer holds the tubes' light alone (no global pass, no other lights).
#include "02_gbuffer/shaders/gbuffer.glsl"

layout(binding = LIGHT_BUFFER_UNIT + 0) uniform sampler2D u_diffuse_light;   // L1
layout(binding = LIGHT_BUFFER_UNIT + 1) uniform sampler2D u_specular_light;  // L2

uniform vec3 u_background;
uniform int u_term;

out vec4 out_color;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  Surface s = decode_gbuffer(pixel);
  vec3 l1 = texelFetch(u_diffuse_light, pixel, 0).rgb, l2 = texelFetch(u_specular_light, pixel, 0).rgb;
  out_color = vec4(s.is_sky ? u_background : (u_term == 1 ? s.albedo * l1 : l2), 1.0);
}
