#version 450
// Forward shading, fragment stage: every light in the storage buffer, for every fragment
// (per pixel), or the interpolated per-vertex result (PER_VERTEX).
#include "01_forward/shaders/lighting.glsl"
#include "01_forward/shaders/surface_normal.glsl"

// Depth and stencil tests before the shader runs, so GL_SAMPLES_PASSED counts exactly the
// fragments this shader shaded.
layout(early_fragment_tests) in;

layout(std430, binding = 0) readonly buffer Lights { GpuLight lights[]; };

layout(binding = 0) uniform sampler2D u_base_color_texture;
layout(binding = 1) uniform sampler2D u_normal_texture;
layout(binding = 2) uniform sampler2D u_emissive_texture;  // glTF: emitted = u_emissive * texel

uniform vec3 u_eye;
uniform vec4 u_base_color;
uniform vec3 u_specular;
uniform float u_exponent;
uniform vec3 u_emissive;
uniform vec3 u_ambient;
uniform bool u_has_normal_map;
uniform float u_normal_scale;
uniform bool u_renormalize;   // false only to show what goes wrong without it
uniform bool u_include_base;  // ambient + emissive (off in the additive light passes)
uniform int u_first_light;
uniform int u_light_count;

in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;
in vec4 v_tangent;
#ifdef PER_VERTEX
in vec3 v_diffuse_light;
in vec3 v_specular_light;
#endif

out vec4 out_color;


void main() {
  vec4 base = u_base_color * texture(u_base_color_texture, v_uv);
  vec3 albedo = base.rgb;
#ifdef PER_VERTEX
  vec3 diffuse = v_diffuse_light, specular = v_specular_light;
#else
  // [per-pixel]
  vec3 n = surface_normal(v_normal, v_tangent, v_position, v_uv, u_renormalize, u_has_normal_map, u_normal_texture,
                          u_normal_scale);
  vec3 to_eye = normalize(u_eye - v_position);
  vec3 diffuse = vec3(0.0), specular = vec3(0.0);
  for (int i = u_first_light; i < u_first_light + u_light_count; ++i) {
    vec3 to_light, radiance;
    light_incident(lights[i], v_position, to_light, radiance);
    blinn_phong(n, to_eye, to_light, radiance, u_exponent, diffuse, specular);
  }
  // [/per-pixel]
#endif
  vec3 color = albedo * diffuse + u_specular * specular;
  if (u_include_base) color += albedo * u_ambient + u_emissive * texture(u_emissive_texture, v_uv).rgb;
  out_color = vec4(color, 1.0);
}
