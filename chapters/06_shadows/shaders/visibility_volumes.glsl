// Chapter 06: the visibility hook with the volumes method. No map: ShadowStage counted the
// sun's shadow volumes in the stencil before the lights and left 1 (lit) or 0 (in a volume)
// per pixel of the G-buffer, read here at the pixel being lit.
#include "03_light_volumes/shaders/hooks/frame_pixel.glsl"
layout(binding = 12) uniform sampler2D sh_volume_visibility;
#define sh_depth sh_volume_visibility  // show_visibility.frag's map view shows this instead

// [volumes-glsl]
float directional_visibility(int index, GpuLight light, Surface s) {
  if (index != 0) return 1.0;
  if (dot(s.normal, -light.direction_range.xyz) <= 0.0) return 1.0;  // faces away, as the maps
  return texelFetch(sh_volume_visibility, ivec2(frame_pixel()), 0).r;
}
// [/volumes-glsl]

float local_visibility(int index, GpuLight light, Surface s) { return 1.0; }
