#version 450
// Chapter 08's addition (add_indirect.glsl) in compute: one invocation per pixel reads L1,
// adds, and writes it back (each pixel is one invocation's alone), on the image unit that
// LightBuffer::image_defines() names. The sum is the blend's: the stored half float and the
// addition's float, rounded once to a half float.
layout(local_size_x = 8, local_size_y = 8) in;
#include "08_ssgi/shaders/add_indirect.glsl"

layout(binding = LIGHT_BUFFER_IMAGE + 0, rgba16f) uniform image2D u_l1;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, imageSize(u_l1)))) return;  // the groups' overhang past the image
  imageStore(u_l1, pixel, imageLoad(u_l1, pixel) + vec4(indirect_diffuse(pixel), 0.0));
}
