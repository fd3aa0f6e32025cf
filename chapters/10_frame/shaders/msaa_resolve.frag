#version 450
// The resolve: the pixel's samples of light tonemapped one by one and then averaged (the
// display values are what the eye should see blended at an edge), or, to show what the source
// warns against, averaged first and tonemapped once. The output encodes sRGB. (The whole
// frame resolves into radiance instead: msaa_resolve_radiance.frag.)
#include "05_hdr/shaders/hdr_math.glsl"

#if MSAA_SAMPLES > 1
layout(binding = 0) uniform sampler2DMS u_radiance;
#else
layout(binding = 0) uniform sampler2D u_radiance;
#endif
uniform int u_operator;
uniform float u_exposure, u_white;
uniform bool u_resolve_first;
out vec4 out_color;

vec3 display(vec3 radiance) { return min(tonemap(u_operator, radiance * u_exposure, u_white), vec3(1.0)); }

void main() {
  // [resolve]
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec3 sum = vec3(0.0);
  for (int i = 0; i < MSAA_SAMPLES; ++i) {
#if MSAA_SAMPLES > 1
    vec3 radiance = texelFetch(u_radiance, pixel, i).rgb;
#else
    vec3 radiance = texelFetch(u_radiance, pixel, 0).rgb;
#endif
    sum += u_resolve_first ? radiance : display(radiance);
  }
  vec3 mean = sum / float(MSAA_SAMPLES);
  out_color = vec4(u_resolve_first ? display(mean) : mean, 1.0);
  // [/resolve]
}
