#version 450
// The light passes, both stencil-tested before the shader runs (early fragment tests, so what
// the stencil rejects is never shaded): PER_SAMPLE off, where the stencil is 0, one invocation
// per pixel lights the pixel's first sample and the output goes to every sample it covers;
// PER_SAMPLE on, where it is 1, reading gl_SampleID makes one invocation per sample, each
// lighting its own sample of the G-buffer at its own position.
#include "10_frame/shaders/msaa_light.glsl"

layout(early_fragment_tests) in;
uniform vec2 u_first_sample_position;  // sample 0 within the pixel (0.5, 0.5 with one sample)
out vec4 out_radiance;

void main() {
  // [shade]
  ivec2 pixel = ivec2(gl_FragCoord.xy);
#ifdef PER_SAMPLE
  Surface s = decode_gbuffer_sample(pixel, gl_SampleID, vec2(pixel) + gl_SamplePosition);
#else
  Surface s = decode_gbuffer_sample(pixel, 0, vec2(pixel) + u_first_sample_position);
#endif
  out_radiance = vec4(frame_radiance(s, pixel), 1.0);
  // [/shade]
}
