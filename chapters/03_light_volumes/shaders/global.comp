#version 450
// The lights that reach every pixel (global_light.glsl) in compute: one invocation per pixel
// writes the light buffer as images (RGBA16F, as LightBuffer makes them), on the image units
// LightBuffer::image_defines() names. A GPU that runs fragment shaders on a few of its cores
// and compute on all of them (chapter 10's budget) runs this faster; elsewhere it is the same
// work. The frame's hooks read this invocation's pixel (FRAME_PIXEL_COMPUTE).
layout(local_size_x = 8, local_size_y = 8) in;
#define FRAME_PIXEL_COMPUTE 1
#include "03_light_volumes/shaders/global_light.glsl"

// [global-comp]
layout(binding = LIGHT_BUFFER_IMAGE + 0, rgba16f) uniform writeonly image2D u_l1;
#ifndef LIGHT_PREPASS
layout(binding = LIGHT_BUFFER_IMAGE + 1, rgba16f) uniform writeonly image2D u_l2;
#endif

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, imageSize(u_l1)))) return;  // the groups' overhang past the image
  vec4 l1, l2;
  global_light(pixel, l1, l2);
  imageStore(u_l1, pixel, l1);
#ifndef LIGHT_PREPASS
  imageStore(u_l2, pixel, l2);
#endif
}
// [/global-comp]
