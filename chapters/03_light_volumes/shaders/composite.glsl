// The final image's colour at a pixel from the G-buffer and the light buffer:
// F = albedo * L1 + L2 + emissive (the thesis's F = Gd (Ld + Ge) + Ls, with our emissive colour
// added on its own), the background where no surface is. The full-screen pass (composite.frag)
// and the compute pass (composite.comp) both call it.
#include "02_gbuffer/shaders/gbuffer.glsl"

layout(binding = LIGHT_BUFFER_UNIT + 0) uniform sampler2D u_diffuse_light;   // L1
layout(binding = LIGHT_BUFFER_UNIT + 1) uniform sampler2D u_specular_light;  // L2

uniform vec3 u_background;

vec3 composite_colour(ivec2 pixel) {
  // [composite]
  Surface s = decode_gbuffer(pixel);
  vec3 l1 = texelFetch(u_diffuse_light, pixel, 0).rgb, l2 = texelFetch(u_specular_light, pixel, 0).rgb;
  return s.is_sky ? u_background : s.albedo * l1 + l2 + s.emissive;
  // [/composite]
}
