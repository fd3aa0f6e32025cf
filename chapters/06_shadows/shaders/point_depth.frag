#version 450
// The linear distance from the light over the far plane, as the depth: what the lookup compares
// with the receiver's own distance (shadow_visibility.glsl's point_visibility).
in vec3 v_world;
uniform vec3 u_light_position;
uniform float u_far;
void main() { gl_FragDepth = distance(v_world, u_light_position) / u_far; }
