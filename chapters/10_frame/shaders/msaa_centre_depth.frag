#version 450
// The depth the light volumes test against on the pixels not marked as edges: the mean of the
// samples' depths (the depth at the pixel's centre, where msaa_surface.glsl lights them),
// written to every sample. A light then covers all the samples of such a pixel or none, as
// the full-screen light does, save where its volume's outline passes within the pixel: there
// its light is near the cut. With each sample's own depth a grazing surface far away, whose
// samples lie metres apart along the view, would take the light at its centre on some
// samples only.
#include "02_gbuffer/shaders/gbuffer.glsl"

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float depth = 0.0;
  for (int i = 0; i < MSAA_SAMPLES; ++i) depth += GB_FETCH(gb_depth, pixel, i).r;
  gl_FragDepth = depth / float(MSAA_SAMPLES);
}
