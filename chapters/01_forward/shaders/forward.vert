#version 450
// Forward shading, vertex stage. With PER_VERTEX defined the lighting is evaluated here
// (Gouraud) and only its result is interpolated; otherwise the surface is passed on and
// the fragment shader lights every pixel.
#include "01_forward/shaders/lighting.glsl"

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
layout(location = 3) in vec4 a_tangent;

uniform mat4 u_model;
uniform mat3 u_normal_matrix;
uniform mat4 u_view_projection;

out vec3 v_position;
out vec3 v_normal;
out vec2 v_uv;
out vec4 v_tangent;

// The multi-pass mode draws the same triangles once per light with depth test EQUAL:
// every pass must produce bit-identical depths.
invariant gl_Position;

#ifdef PER_VERTEX
layout(std430, binding = 0) readonly buffer Lights { GpuLight lights[]; };
uniform vec3 u_eye;
uniform float u_exponent;
uniform int u_first_light;
uniform int u_light_count;
out vec3 v_diffuse_light;
out vec3 v_specular_light;
#endif

void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  v_position = world.xyz;
  v_normal = u_normal_matrix * a_normal;
  v_uv = a_uv;
  v_tangent = vec4(mat3(u_model) * a_tangent.xyz, a_tangent.w);
  gl_Position = u_view_projection * world;
#ifdef PER_VERTEX
  // [per-vertex]
  vec3 n = normalize(v_normal);
  vec3 to_eye = normalize(u_eye - v_position);
  vec3 diffuse = vec3(0.0), specular = vec3(0.0);
  for (int i = u_first_light; i < u_first_light + u_light_count; ++i) {
    vec3 to_light, radiance;
    light_incident(lights[i], v_position, to_light, radiance);
    blinn_phong(n, to_eye, to_light, radiance, u_exponent, diffuse, specular);
  }
  v_diffuse_light = diffuse;    // interpolated linearly across the triangle:
  v_specular_light = specular;  // a highlight between vertices is simply lost
  // [/per-vertex]
#endif
}
