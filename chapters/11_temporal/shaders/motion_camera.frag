#version 450
// Every pixel moved by the camera alone: its G-buffer position (on the far plane for the sky)
// seen by this frame's and the last frame's camera.
#include "02_gbuffer/shaders/gbuffer.glsl"
#include "11_temporal/shaders/motion.glsl"

uniform mat4 u_current_view_projection;
uniform mat4 u_previous_view_projection;
out vec4 out_motion;

void main() {
  Surface s = decode_gbuffer(ivec2(gl_FragCoord.xy));
  vec4 world = vec4(s.position, 1.0);
  out_motion = motion_of(u_current_view_projection * world, u_previous_view_projection * world);
}
