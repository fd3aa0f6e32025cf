#version 450
// The subgroup operations of shade.glsl's shared-list loop, where ClusteredLights found them.
#if defined(SUBGROUP_KHR)
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_ballot : require
#elif defined(SUBGROUP_ARB)
#extension GL_ARB_shader_group_vote : require
#extension GL_ARB_shader_ballot : require
#endif
// Pass 3 in compute: one invocation per pixel adds its cell's lights into the light buffer
// (read, add, write: each pixel is one invocation's alone).
layout(local_size_x = 8, local_size_y = 8) in;
#define FRAME_PIXEL_COMPUTE 1  // the frame's hooks read this invocation's pixel
#include "09_clustered/shaders/shade.glsl"

layout(binding = LIGHT_BUFFER_IMAGE + 0, rgba16f) uniform image2D u_l1;  // LightBuffer::image_defines()
layout(binding = LIGHT_BUFFER_IMAGE + 1, rgba16f) uniform image2D u_l2;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, u_grid.xy))) return;
  vec4 l1, l2;
  pixel_output(pixel, l1, l2);
  imageStore(u_l1, pixel, imageLoad(u_l1, pixel) + l1);
  imageStore(u_l2, pixel, imageLoad(u_l2, pixel) + l2);
}
