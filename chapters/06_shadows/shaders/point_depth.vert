#version 450
// A point light's cube map face (cube_math.h): the scene from the light, the world position on.
layout(location = 0) in vec3 a_position;
uniform mat4 u_light_view_projection;
uniform mat4 u_model;
out vec3 v_world;
void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  v_world = world.xyz;
  gl_Position = u_light_view_projection * world;
}
