#version 450
// The shadow map's depth pass: the scene's triangles seen from the light, nothing but depth.
layout(location = 0) in vec3 a_position;
uniform mat4 u_light_view_projection;
uniform mat4 u_model;
void main() { gl_Position = u_light_view_projection * (u_model * vec4(a_position, 1.0)); }
