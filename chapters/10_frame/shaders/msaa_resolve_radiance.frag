#version 450
// The whole frame's resolve (--msaa N): the pixel's samples of light into one float radiance
// for chapter 05's HDR chain, which needs linear light (its log-average and bloom) but
// tonemaps only after it. A plain mean lets one bright sample (a lamp behind an edge) fill
// the pixel, where the tonemapped samples would have blended; so each sample is weighted by
// the slope of the curve T(x) = x / (1 + x) at its exposed luminance, which is the mean of
// T over the samples mapped back through T's inverse (Karis's tonemap-resolve-inverse).
// u_resolve_first: the plain mean, to be seen (--msaa-view resolve-first).
#if MSAA_SAMPLES > 1
layout(binding = 0) uniform sampler2DMS u_radiance;
#else
layout(binding = 0) uniform sampler2D u_radiance;
#endif
uniform float u_exposure;  // the exposure the chain last applied: where the curve bends
uniform bool u_resolve_first;
out vec4 out_color;

vec3 sample_radiance(ivec2 pixel, int i) {
#if MSAA_SAMPLES > 1
  return texelFetch(u_radiance, pixel, i).rgb;
#else
  return texelFetch(u_radiance, pixel, 0).rgb;
#endif
}

// How much the curve keeps of this sample: 1 for dark light, 1 / (1 + L) for bright.
float tone_weight(vec3 radiance) {
  float luminance = dot(radiance, vec3(0.2126, 0.7152, 0.0722)) * u_exposure;
  return 1.0 / (1.0 + max(luminance, 0.0));
}

// Exercise 3 (chapters/10_frame/exercises/resolve.glsl) stands in for it.
#ifdef EXERCISE_RESOLVE
#include EXERCISE_RESOLVE
#else
void main() {
  // [resolve]
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec3 sum = vec3(0.0);
  float weights = 0.0;
  for (int i = 0; i < MSAA_SAMPLES; ++i) {
    vec3 radiance = sample_radiance(pixel, i);
    float w = u_resolve_first ? 1.0 : tone_weight(radiance);
    sum += w * radiance;
    weights += w;
  }
  out_color = vec4(sum / weights, 1.0);
  // [/resolve]
}
#endif
