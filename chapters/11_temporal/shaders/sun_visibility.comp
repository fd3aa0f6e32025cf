#version 450
// The sun's visibility at each pixel of the G-buffer, before the lights: chapter 06's own hook
// (shadow_visibility.glsl's directional_visibility, with the shadow stage's defines and block:
// this frame's part of PCSS's disk, turned this frame), for chapter 11 to accumulate
// (temporal_shadows.h). Also PCSS's penumbra radius there (0: its search found no blocker).
layout(local_size_x = 8, local_size_y = 8) in;
#define FRAME_PIXEL_COMPUTE 1  // the hook's rotated disk reads this invocation's pixel
#include "01_forward/shaders/lighting.glsl"
#include "02_gbuffer/shaders/gbuffer.glsl"
#include "06_shadows/shaders/shadow_visibility.glsl"
layout(r32f, binding = 0) writeonly uniform image2D u_visibility;
layout(r32f, binding = 1) writeonly uniform image2D u_radius;
uniform vec3 u_sun_direction;  // the direction the sun shines

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(u_visibility)))) return;
  Surface s = decode_gbuffer(p);
  float v = 1.0;
  if (!s.is_sky) {
    GpuLight sun = GpuLight(vec4(0.0), vec4(u_sun_direction, 0.0), vec4(1.0), vec4(0.0));
    v = directional_visibility(SHADOW_SUN_INDEX, sun, s);
  }
  imageStore(u_visibility, p, vec4(v, 0.0, 0.0, 0.0));
  imageStore(u_radius, p, vec4(sh_pcss_radius, 0.0, 0.0, 0.0));
}
