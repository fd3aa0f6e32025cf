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
  out_radiance = vec4(frame_radiance(msaa_surface(pixel), pixel), 1.0);
  // [/shade]
}
