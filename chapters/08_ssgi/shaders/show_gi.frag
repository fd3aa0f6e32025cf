#version 450
// Chapter 08's pictures: the indirect light the pixel reflects, albedo x L1_ind (u_mode 0),
// the AO term as grey (1), an RGB picture the program computed (2: the truth, as albedo x its
// L1_ind) or a heat map of a one-channel error in the red channel (3: black 0 ... red u_heat),
// or the back-face layer: the light its surfaces send, albedo x L1 (4). The pictures (2, 3) are
// the screen's size: with a guard band they start u_picture_offset pixels in.
#include "02_gbuffer/shaders/gbuffer.glsl"
layout(binding = GI_UNIT + 0) uniform sampler2D u_gi;  // the stage's units (GiStage)
layout(binding = GI_UNIT + 1) uniform sampler2D u_back_albedo;
layout(binding = GI_UNIT + 2) uniform sampler2D u_back_light;
uniform int u_mode;
uniform int u_picture_offset;  // pixels, on both axes
uniform float u_exposure, u_heat;
out vec4 colour;
void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  if (u_mode == 4) {
    colour = vec4(texelFetch(u_back_albedo, pixel, 0).rgb * max(texelFetch(u_back_light, pixel, 0).rgb, vec3(0.0)), 1.0);
    return;
  }
  ivec2 at = u_mode >= 2 ? pixel - ivec2(u_picture_offset) : pixel;
  if (u_mode >= 2 && (any(lessThan(at, ivec2(0))) || any(greaterThanEqual(at, textureSize(u_gi, 0))))) {
    colour = vec4(0.0, 0.0, 0.0, 1.0);  // the guard band around a screen-sized picture
    return;
  }
  vec4 gi = texelFetch(u_gi, at, 0);
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
