#version 450
// Clustered forward for the opaque scene: chapter 01's vertex stage and material, the surface
// built as geometry.frag stores it, lit from the cluster lists (clustered_forward.glsl). It
// writes what the deferred shading adds into the light buffer, L1 (diffuse) and L2 (specular,
// tinted), so the two can be compared pixel for pixel; chapter 10's glass uses the include.
#include "01_forward/shaders/surface_normal.glsl"
#include "09_clustered/shaders/clustered_forward.glsl"

layout(early_fragment_tests) in;

layout(binding = 0) uniform sampler2D u_base_color_texture;
layout(binding = 1) uniform sampler2D u_normal_texture;

uniform vec4 u_base_color;
uniform vec3 u_specular;
uniform float u_exponent;
uniform bool u_has_normal_map;
uniform float u_normal_scale;

in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;
in vec4 v_tangent;

layout(location = 0) out vec4 out_diffuse;
layout(location = 1) out vec4 out_specular;

void main() {
  Surface s;
  s.position = v_position;
  s.normal = surface_normal(v_normal, v_tangent, v_position, v_uv, true, u_has_normal_map, u_normal_texture, u_normal_scale);
  s.albedo = (u_base_color * texture(u_base_color_texture, v_uv)).rgb;
  s.specular = u_specular;
  s.exponent = u_exponent;
  s.emissive = vec3(0.0);
  s.is_sky = false;
  s.depth = gl_FragCoord.z;
  vec3 diffuse, specular;
  uint evaluated, lit;
  clustered_forward(s, gl_FragCoord.xy, diffuse, specular, evaluated, lit);
#if defined(HEAT_SHADED)
  out_diffuse = vec4(float(evaluated));
  out_specular = vec4(0.0);
#elif defined(HEAT_LIT)
  out_diffuse = vec4(float(lit));
  out_specular = vec4(0.0);
#else
  out_diffuse = vec4(diffuse, 0.0);
  out_specular = vec4(specular, 0.0);
#endif
}
