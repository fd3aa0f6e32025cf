#version 450
// Chapter 04's forward pass: chapter 01's lights, then every neon tube by the selected
// method, for every fragment. The chapter's default path calls the same neon_light() once per
// pixel of each tube's capsule over the G-buffer instead (neon_volume.frag); this pass is the
// yardstick the tests hold it to (--forward 1).
#include "01_forward/shaders/lighting.glsl"
#include "04_neon/shaders/neon.glsl"
#include "01_forward/shaders/surface_normal.glsl"

layout(early_fragment_tests) in;

layout(std430, binding = 0) readonly buffer Lights { GpuLight lights[]; };
layout(std430, binding = 1) readonly buffer Neons { NeonGpu neons[]; };

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
uniform int u_light_count;
uniform int u_neon_count;
uniform int u_method;   // NEON_* in neon.glsl
uniform int u_samples;  // ground truth: samples per tube; points: point lights per tube
uniform int u_term;     // 0: the whole image; 1: neon diffuse only; 2: neon specular only

in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;
in vec4 v_tangent;

out vec4 out_color;

void main() {
  vec3 albedo = (u_base_color * texture(u_base_color_texture, v_uv)).rgb;
  // The normal every pass uses (chapter 01), normal map included, so this yardstick bends the
  // same normals as the G-buffer it is held against.
  vec3 n = surface_normal(v_normal, v_tangent, v_position, v_uv, true, u_has_normal_map, u_normal_texture, u_normal_scale);
  vec3 to_eye = normalize(u_eye - v_position);
  vec3 diffuse = vec3(0.0), specular = vec3(0.0);
  if (u_term == 0) {
    for (int i = 0; i < u_light_count; ++i) {
      vec3 to_light, radiance;
      light_incident(lights[i], v_position, to_light, radiance);
      blinn_phong(n, to_eye, to_light, radiance, u_exponent, diffuse, specular);
    }
  }
  // [neon-per-fragment]
  NeonSurface surface = NeonSurface(v_position, n, to_eye, u_exponent);
  for (int i = 0; i < u_neon_count; ++i) {
    NeonResult r = neon_light(surface, neons[i], NeonMethod(u_method, u_samples));
    diffuse += r.diffuse;
    specular += r.specular;
  }
  // [/neon-per-fragment]
  vec3 color = vec3(0.0);
  if (u_term != 2) color += albedo * diffuse;
  if (u_term != 1) color += u_specular * specular;
  if (u_term == 0) color += albedo * u_ambient + u_emissive * texture(u_emissive_texture, v_uv).rgb;
  out_color = vec4(color, 1.0);
}
