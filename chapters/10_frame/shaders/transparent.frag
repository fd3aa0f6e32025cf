#version 450
// Chapter 10: a blended surface (glTF alphaMode BLEND), shaded forward after the deferred
// passes with the frame's lights: the directional ones as chapter 03's global pass lights
// them, the local ones from chapter 09's cluster lists (clustered_forward.glsl: chapter 03's
// cut and local_light(), the frame's visibility hook). Compiled with
// ClusteredLights::forward_defines() and one of three outputs:
//   GLASS_OVER     premultiplied colour for "over" blending, back to front (sorted);
//   GLASS_WBOIT    weighted blended OIT: the weighted colour sum and the coverage (McGuire & Bavoil 2013);
//   GLASS_CAPTURE  every fragment appended to a list (the exact order, sorted on the CPU).
// (it brings lighting.glsl, gbuffer.glsl and FRAME_VISIBILITY with it)
#include "09_clustered/shaders/clustered_forward.glsl"
#include "01_forward/shaders/surface_normal.glsl"

// The depth test (against the G-buffer's depth) before the shader: hidden glass is never
// shaded, never captured, and GL_SAMPLES_PASSED counts exactly the fragments shaded.
layout(early_fragment_tests) in;

layout(std430, binding = 3) readonly buffer Directional { GpuLight directional[]; };

layout(binding = 0) uniform sampler2D u_base_color_texture;
layout(binding = 1) uniform sampler2D u_normal_texture;
layout(binding = 2) uniform sampler2D u_emissive_texture;

uniform vec3 u_eye;
uniform vec4 u_base_color;
uniform vec3 u_specular;
uniform float u_exponent;
uniform vec3 u_emissive;
uniform bool u_has_normal_map;
uniform float u_normal_scale;
uniform vec3 u_ambient;
uniform int u_light_count;  // directional lights

in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;
in vec4 v_tangent;

// [glass-shading]
// Chapter 01's per-pixel Blinn-Phong (lighting.glsl), as the opaque surfaces are lit: the
// directional lights with the frame's visibility (the sun's shadow), the local lights from
// the fragment's cluster; the normal as every pass reads it (chapter 01's surface_normal():
// renormalised, bent by the material's normal map).
// The result premultiplied by the coverage alpha: the surface adds alpha of its colour and
// lets (1 - alpha) of what is behind through.
vec4 glass_colour() {
  vec4 base = u_base_color * texture(u_base_color_texture, v_uv);
  Surface s;
  s.position = v_position;
  s.normal = surface_normal(v_normal, v_tangent, v_position, v_uv, true, u_has_normal_map, u_normal_texture, u_normal_scale);
  s.albedo = base.rgb;
  s.specular = u_specular;
  s.exponent = u_exponent;
  s.emissive = vec3(0.0);
  s.is_sky = false;
  s.depth = gl_FragCoord.z;
  vec3 to_eye = normalize(u_eye - v_position);
  vec3 diffuse = vec3(0.0), specular = vec3(0.0);
  for (int i = 0; i < u_light_count; ++i) {
    vec3 to_light, radiance;
    light_incident(directional[i], v_position, to_light, radiance);
    radiance *= directional_visibility(i, directional[i], s);
    blinn_phong(s.normal, to_eye, to_light, radiance, u_exponent, diffuse, specular);
  }
  vec3 local_diffuse, local_specular;  // local_specular is tinted by s.specular already
  uint evaluated, lit;
  clustered_forward(s, gl_FragCoord.xy, local_diffuse, local_specular, evaluated, lit);
  vec3 colour = base.rgb * (diffuse + local_diffuse + u_ambient) + u_specular * specular + local_specular
              + u_emissive * texture(u_emissive_texture, v_uv).rgb;
  return vec4(colour * base.a, base.a);
}
// [/glass-shading]

float view_depth() { return -(u_view * vec4(v_position, 1.0)).z; }

#if defined(GLASS_WBOIT)
layout(location = 0) out vec4 out_accumulation;
layout(location = 1) out vec4 out_revealage;
// McGuire and Bavoil's depth weight, in a file of its own that the twin test includes too;
// exercise 1 (chapters/10_frame/exercises/wboit_weight.glsl) stands in for it.
#ifdef EXERCISE_WBOIT_WEIGHT
#include EXERCISE_WBOIT_WEIGHT
#else
#include "10_frame/shaders/wboit_weight.glsl"
#endif
void main() {
  vec4 c = glass_colour();
  // [wboit-accumulate]
  out_accumulation = c * wboit_weight(view_depth(), c.a);  // blended ONE, ONE: w (alpha c, alpha) summed
  out_revealage = vec4(c.a);  // blended ZERO, ONE_MINUS_SRC_COLOR: revealage *= (1 - alpha)
  // [/wboit-accumulate]
}
#elif defined(GLASS_CAPTURE)
struct Fragment { uint pixel; uint rank; float depth; float pad; vec4 colour; };
layout(std430, binding = 6) writeonly buffer Fragments { Fragment fragments[]; };
layout(std430, binding = 7) buffer Counter { uint fragment_count; };
uniform vec2 u_size;
uniform int u_rank;
uniform int u_capacity;
void main() {
  uint i = atomicAdd(fragment_count, 1u);  // counts past the capacity: the overflow is seen
  if (i >= uint(u_capacity)) return;
  ivec2 p = ivec2(gl_FragCoord.xy);
  fragments[i] = Fragment(uint(p.y) * uint(u_size.x) + uint(p.x), uint(u_rank), view_depth(), 0.0, glass_colour());
}
#else
out vec4 out_color;
void main() { out_color = glass_colour(); }
#endif
