#version 450
// The sun's shadow volumes (shadow_volumes.h): world-space homogeneous corners, w = 1 on the
// caster, w = 0 at infinity along the light; the camera's view-projection takes both.
layout(location = 0) in vec4 a_position;
uniform mat4 u_view_projection;
void main() { gl_Position = u_view_projection * a_position; }
