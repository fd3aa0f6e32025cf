// Chapter 07's ambient hook (deferred_frame.h's FRAME_AMBIENT): the ambient light times the
// visibility A of the AO texture the AoStage binds on its unit (AO_UNIT). Only the ambient: the direct
// lights keep their own visibility (chapter 06's shadows). A lower-resolution AO texture is
// read at the texel that covers the pixel.
// [ambient-hook]
layout(binding = AO_UNIT) uniform sampler2D u_ao;
vec3 ambient_light(vec3 ambient, Surface s, ivec2 pixel) {
  ivec2 size = textureSize(u_ao, 0);
  ivec2 texel = min(pixel * size / ivec2(gb_size.xy), size - 1);
  return ambient * texelFetch(u_ao, texel, 0).r;
}
// [/ambient-hook]
