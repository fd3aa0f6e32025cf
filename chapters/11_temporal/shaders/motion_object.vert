#version 450
// The object pass: each vertex where it is now and where it was (its instance's last model
// matrix), seen by this frame's and the last frame's camera without jitter. gl_Position is
// computed as chapter 02's geometry pass computes it, so the depth test against its depth
// passes on the same surfaces.
layout(location = 0) in vec3 a_position;

uniform mat4 u_model;
uniform mat4 u_previous_model;
uniform mat4 u_view_projection;           // the G-buffer's (jittered, in its depth format)
uniform mat4 u_current_view_projection;   // without jitter
uniform mat4 u_previous_view_projection;  // without jitter

out vec4 v_clip_now;
out vec4 v_clip_then;

invariant gl_Position;

void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  v_clip_now = u_current_view_projection * world;
  v_clip_then = u_previous_view_projection * (u_previous_model * vec4(a_position, 1.0));
  gl_Position = u_view_projection * world;
}
