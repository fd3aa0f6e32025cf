#version 450
// The final image (composite.glsl) in compute: one invocation a pixel writes a float target
// (RGBA16F) as an image, on the unit COMPOSITE_IMAGE (LightVolumes::composite_compute). The
// same colour as the full-screen pass; a GPU that runs fragment shaders on a few of its cores
// and compute on all of them (chapter 10's budget) runs it faster.
layout(local_size_x = 8, local_size_y = 8) in;
#include "03_light_volumes/shaders/composite.glsl"

// [composite-comp]
layout(binding = COMPOSITE_IMAGE, rgba16f) uniform writeonly image2D u_output;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, imageSize(u_output)))) return;  // the groups' overhang past the image
  imageStore(u_output, pixel, vec4(composite_colour(pixel), 1.0));
}
// [/composite-comp]
