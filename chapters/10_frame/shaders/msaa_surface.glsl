// The surface a light pass of the MSAA frame lights. PER_SAMPLE: its own sample at its own
// position (reading gl_SampleID makes one invocation per sample, writing only that sample).
// Otherwise: the pixel's surface at its centre, for every sample the output goes to. The
// full-screen passes (msaa_shade.frag) and the light volumes (msaa_volume.frag) both read it,
// so both ways of bringing the lights light the same surface.
#include "01_forward/shaders/lighting.glsl"
#include "02_gbuffer/shaders/gbuffer.glsl"
#include FRAME_VISIBILITY  // chapter 03's hooks/full_visibility.glsl
#include "03_light_volumes/shaders/local_light.glsl"

Surface msaa_surface(ivec2 pixel) {
  // [surface]
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
  // [/surface]
  return s;
}
