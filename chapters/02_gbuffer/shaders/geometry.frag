#version 450
// The geometry pass: one fragment writes every target of the G-buffer at once (multiple
// render targets). Nothing is lit here; the surface is only described. The vertex stage is
// chapter 01's forward.vert, so both chapters cover exactly the same pixels.
#include "01_forward/shaders/surface_normal.glsl"
#include "02_gbuffer/shaders/encoding.glsl"

layout(early_fragment_tests) in;  // GL_SAMPLES_PASSED = fragments written

layout(binding = 0) uniform sampler2D u_base_color_texture;
layout(binding = 1) uniform sampler2D u_normal_texture;
layout(binding = 2) uniform sampler2D u_emissive_texture;

uniform vec4 u_base_color;
uniform vec3 u_specular;
uniform float u_exponent;
uniform int u_emissive_code;        // palette layouts: which emissive colour (0: none)
uniform float u_emissive_strength;  // the source layout: emissive = albedo * strength
uniform bool u_has_normal_map;
uniform float u_normal_scale;

in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;
in vec4 v_tangent;

// [targets]
layout(location = 0) out vec4 out_albedo;    // rgb albedo, a emissive
layout(location = 1) out vec4 out_specular;  // rgb specular colour, a exponent
layout(location = 2) out vec4 out_normal;    // encoded normal (+ control bits)
#if defined(GBUFFER_DEPTH_COPY)
layout(location = 3) out float out_depth;    // the source's G4: window depth as a float
#elif defined(GBUFFER_STORED_POSITION)
layout(location = 3) out vec4 out_position;  // the float reference: world position
#endif
// [/targets]


void main() {
  vec3 albedo = (u_base_color * texture(u_base_color_texture, v_uv)).rgb;
  vec3 n = surface_normal(v_normal, v_tangent, v_position, v_uv, true, u_has_normal_map, u_normal_texture, u_normal_scale);
  // glTF emits emissiveFactor x emissiveTexture. The G-buffer keeps one emissive colour per
  // material (a palette code) or one strength, so a texture can only scale the strength or,
  // for a code, gate it: texels at least half bright emit the material's colour, others none.
  vec3 e = texture(u_emissive_texture, v_uv).rgb;
  float emission = max(e.r, max(e.g, e.b));
  // [write-targets]
#ifdef GBUFFER_EMISSIVE_ALBEDO_SCALE
  out_albedo = vec4(albedo, u_emissive_strength * emission);
#else
  out_albedo = vec4(albedo, float(emission >= 0.5 ? u_emissive_code : 0) / 255.0);
#endif
#ifdef GBUFFER_FLOAT_EXPONENT
  out_specular = vec4(u_specular, u_exponent);
#else
  out_specular = vec4(u_specular, encode_exponent(u_exponent));
#endif
#if defined(GBUFFER_NORMAL_FLOAT)
  out_normal = vec4(n, 1.0);
#elif defined(GBUFFER_NORMAL_XYZ)
  out_normal = vec4(encode_xyz(n), 1.0);  // alpha: control value "geometry here"
#else
  out_normal = vec4(encode_octahedral(n, GBUFFER_NORMAL_OCT), 0.0, 1.0);
#endif
#if defined(GBUFFER_DEPTH_COPY)
  out_depth = gl_FragCoord.z;
#elif defined(GBUFFER_STORED_POSITION)
  out_position = vec4(v_position, 1.0);
#endif
  // [/write-targets]
}
