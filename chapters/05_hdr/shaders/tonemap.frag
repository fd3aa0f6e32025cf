#version 450
// The last pass of the frame: exposure, bloom, the tonemapping curve, and the sRGB encoding
// (done by the framebuffer: this shader writes linear values).
#include "05_hdr/shaders/hdr_math.glsl"

layout(binding = 0) uniform sampler2D u_radiance;
layout(binding = 1) uniform sampler2D u_bloom;   // blur level, bilinear, clamped to the edge
layout(std430, binding = EXPOSURE_BINDING) readonly buffer State { ExposureState state; };

#define BLOOM_OFF 0
#define BLOOM_AFTER 1     // the source: added to the tonemapped image
#define BLOOM_BEFORE 2    // energy-conserving: moved within the HDR image, then tonemapped
#define VIEW_FINAL 0
#define VIEW_BLOOM 1      // the bloom texture alone, in exposed units

uniform int u_operator;
uniform float u_white;
uniform int u_bloom_mode;
uniform float u_bloom_strength, u_bloom_threshold, u_bloom_limit;
uniform vec2 u_bloom_uv_scale;
uniform int u_view;

out vec4 out_color;

void main() {
  bool valid;
  vec3 radiance = sanitize(texelFetch(u_radiance, ivec2(gl_FragCoord.xy), 0).rgb, valid);
  // Texel i of the blur level covers pixels [i 2^l, (i + 1) 2^l): bilinear upsampling.
  vec3 bloom = u_bloom_mode != BLOOM_OFF ? texture(u_bloom, gl_FragCoord.xy * u_bloom_uv_scale).rgb : vec3(0.0);
  if (u_view == VIEW_BLOOM) {
    out_color = vec4(bloom, 1.0);
    return;
  }
  // [tonemap]
  vec3 x = radiance * state.exposure;
  if (u_bloom_mode == BLOOM_BEFORE) {
    // Take the bright part out where it was and put it back spread out: the blur's weights
    // sum to 1, so the image keeps its total light.
    x += u_bloom_strength * (bloom - bright_pass(x, u_bloom_threshold, u_bloom_limit));
  }
  vec3 display = tonemap(u_operator, x, u_white);
  if (u_bloom_mode == BLOOM_AFTER) display += u_bloom_strength * bloom;  // as in the source
  out_color = vec4(min(display, vec3(1.0)), 1.0);
  // [/tonemap]
}
