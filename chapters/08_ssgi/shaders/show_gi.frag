#version 450
// Chapter 08's pictures: the indirect light the pixel reflects, albedo x L1_ind (u_mode 0),
// the AO term as grey (1), an RGB picture the program computed (2: the truth, as albedo x its
// L1_ind) or a heat map of a one-channel error in the red channel (3: black 0 ... red u_heat).
#include "02_gbuffer/shaders/gbuffer.glsl"
layout(binding = 8) uniform sampler2D u_gi;
uniform int u_mode;
uniform float u_exposure, u_heat;
out vec4 colour;
void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 gi = texelFetch(u_gi, pixel, 0);
  Surface s = decode_gbuffer(pixel);
  if (u_mode == 1) { colour = vec4(vec3(gi.a), 1.0); return; }
  if (u_mode == 3) {
    float t = clamp(gi.r / u_heat, 0.0, 1.0);
    vec3 c = t < 0.25 ? mix(vec3(0.0), vec3(0.0, 0.0, 1.0), t / 0.25)
           : t < 0.5  ? mix(vec3(0.0, 0.0, 1.0), vec3(0.0, 1.0, 0.0), (t - 0.25) / 0.25)
           : t < 0.75 ? mix(vec3(0.0, 1.0, 0.0), vec3(1.0, 1.0, 0.0), (t - 0.5) / 0.25)
                      : mix(vec3(1.0, 1.0, 0.0), vec3(1.0, 0.0, 0.0), (t - 0.75) / 0.25);
    colour = vec4(c, 1.0);
    return;
  }
  colour = vec4(s.is_sky ? vec3(0.0) : u_exposure * s.albedo * max(gi.rgb, vec3(0.0)), 1.0);
}
