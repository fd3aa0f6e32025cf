#version 450
// Chapter 08's back-face layer: chapter 02's G-buffer targets for the nearest back face (the
// pass culls front faces). The normal kept is the surface's own, facing away from the camera:
// chapter 01's surface_normal() turns a back face's normal toward the viewer (glTF's rule for
// doubleSided materials), which the layer undoes. Emissive code 0: a back face's emission is
// not bounced (as the front layer's is not: gi_truth.h). No early fragment tests: the layer
// discards the near side of doubleSided materials, which SceneGpu::draw draws unculled.
#include "01_forward/shaders/surface_normal.glsl"
#include "02_gbuffer/shaders/encoding.glsl"

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

layout(location = 0) out vec4 out_albedo;
layout(location = 1) out vec4 out_specular;
layout(location = 2) out vec4 out_normal;
#if defined(GBUFFER_DEPTH_COPY)
layout(location = 3) out float out_depth;
#elif defined(GBUFFER_STORED_POSITION)
layout(location = 3) out vec4 out_position;
#endif

void main() {
  if (gl_FrontFacing) discard;  // a doubleSided material's near side: the front layer has it
  vec3 albedo = (u_base_color * texture(u_base_color_texture, v_uv)).rgb;
  vec3 n = -surface_normal(v_normal, v_tangent, v_position, v_uv, true, u_has_normal_map, u_normal_texture, u_normal_scale);
  out_albedo = vec4(albedo, 0.0);
#ifdef GBUFFER_FLOAT_EXPONENT
  out_specular = vec4(u_specular, u_exponent);
#else
  out_specular = vec4(u_specular, encode_exponent(u_exponent));
#endif
#if defined(GBUFFER_NORMAL_FLOAT)
  out_normal = vec4(n, 1.0);
#elif defined(GBUFFER_NORMAL_XYZ)
  out_normal = vec4(encode_xyz(n), 1.0);
#else
  out_normal = vec4(encode_octahedral(n, GBUFFER_NORMAL_OCT), 0.0, 1.0);
#endif
#if defined(GBUFFER_DEPTH_COPY)
  out_depth = gl_FragCoord.z;
#elif defined(GBUFFER_STORED_POSITION)
  out_position = vec4(v_position, 1.0);
#endif
}
