#version 450
// The light passes, both stencil-tested before the shader runs (early fragment tests, so what
// the stencil rejects is never shaded): PER_SAMPLE off, where the stencil is 0, one invocation
// per pixel lights the pixel's surface at its centre and the output goes to every sample;
// PER_SAMPLE on, where it is 1, reading gl_SampleID makes one invocation per sample, each
// lighting its own sample of the G-buffer at its own position.
#include "10_frame/shaders/msaa_light.glsl"

layout(early_fragment_tests) in;
out vec4 out_radiance;

void main() {
  // [shade]
  ivec2 pixel = ivec2(gl_FragCoord.xy);
#ifdef PER_SAMPLE
  Surface s = decode_gbuffer_sample(pixel, gl_SampleID, vec2(pixel) + gl_SamplePosition);
#else
  // Every sample here lies in one plane, and the sample pattern is symmetric about the pixel
  // centre: the mean of their depths is the depth at the centre, where the light is computed
  // (as the frame without MSAA does; sample 0 alone would shift the image by its offset).
  Surface s = decode_gbuffer_sample(pixel, 0, vec2(pixel) + 0.5);
  float depth = 0.0;
  for (int i = 0; i < MSAA_SAMPLES; ++i) depth += GB_FETCH(gb_depth, pixel, i).r;
  if (!s.is_sky) s.position = reconstruct_position(vec2(pixel) + 0.5, depth / float(MSAA_SAMPLES));
#endif
  out_radiance = vec4(frame_radiance(s, pixel), 1.0);
  // [/shade]
}
