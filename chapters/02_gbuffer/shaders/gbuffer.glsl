// Reading the G-buffer back: the samplers, the frame block, and decode_gbuffer(), which
// turns one pixel into the surface the lighting model needs. Compile with the defines of
// GBuffer::shader_defines(first_unit) (see gbuffer.h for the contract), e.g.
//   #include "02_gbuffer/shaders/gbuffer.glsl"
//   Surface s = decode_gbuffer(ivec2(gl_FragCoord.xy));
#include "02_gbuffer/shaders/encoding.glsl"

#ifndef GBUFFER_FIRST_UNIT
#error "gbuffer.glsl needs the defines of GBuffer::shader_defines()"
#endif

// Chapter 10's MSAA: with GBUFFER_SAMPLES every target is multisampled and each sample is
// read apart (decode_gbuffer_sample); single-sampled, the sample index is 0.
#ifdef GBUFFER_SAMPLES
#define GB_SAMPLER sampler2DMS
#define GB_FETCH(t, pixel, sample) texelFetch(t, pixel, sample)
#else
#define GB_SAMPLER sampler2D
#define GB_FETCH(t, pixel, sample) texelFetch(t, pixel, 0)
#endif
layout(binding = GBUFFER_FIRST_UNIT + 0) uniform GB_SAMPLER gb_albedo;    // rgb albedo, a emissive code
layout(binding = GBUFFER_FIRST_UNIT + 1) uniform GB_SAMPLER gb_specular;  // rgb colour, a exponent code
layout(binding = GBUFFER_FIRST_UNIT + 2) uniform GB_SAMPLER gb_normal;
layout(binding = GBUFFER_FIRST_UNIT + 3) uniform GB_SAMPLER gb_depth;     // window depth
#ifdef GBUFFER_STORED_POSITION
layout(binding = GBUFFER_FIRST_UNIT + 4) uniform GB_SAMPLER gb_position;  // the float reference only
#endif

// [frame-block-glsl]
layout(std140, binding = GBUFFER_FRAME_BINDING) uniform GBufferFrame {
#include "02_gbuffer/shaders/gbuffer_frame.h"
};
// [/frame-block-glsl]

// [surface-struct]
struct Surface {
  vec3 position;   // world space
  vec3 normal;     // world space, unit length (zero for the sky)
  vec3 albedo;     // linear
  vec3 specular;   // linear specular colour
  float exponent;  // Blinn-Phong exponent
  vec3 emissive;   // linear radiance the surface emits
  bool is_sky;     // no geometry at this pixel: nothing to light
  float depth;     // the stored window depth
};
// [/surface-struct]

// Exercise 3 (chapters/02_gbuffer/exercises/reconstruct_position.glsl) stands in with --exercise 3.
#ifdef EXERCISE_RECONSTRUCT_POSITION
#include EXERCISE_RECONSTRUCT_POSITION
#else
// [reconstruct-glsl]
// The world position of a pixel from its depth. The pixel centre and the depth give the
// point in normalised device coordinates; the inverse view-projection takes it back to
// homogeneous world coordinates, and the divide by w undoes the perspective.
vec3 reconstruct_position(vec2 pixel_centre, float depth) {
  vec2 ndc_xy = pixel_centre * gb_size.zw * 2.0 - 1.0;
#ifdef GBUFFER_REVERSED_Z
  float ndc_z = depth;              // glClipControl(..., GL_ZERO_TO_ONE): depth = z / w
#else
  float ndc_z = depth * 2.0 - 1.0;  // OpenGL's default: depth = (z / w + 1) / 2
#endif
  vec4 world = gb_inverse_view_projection * vec4(ndc_xy, ndc_z, 1.0);
  return world.xyz / world.w;
}
// [/reconstruct-glsl]
#endif

vec3 decode_normal(vec4 stored) {
#if defined(GBUFFER_NORMAL_FLOAT)
  return normalize(stored.xyz);
#elif defined(GBUFFER_NORMAL_XYZ)
  return decode_xyz(stored.xyz);
#else
  return decode_octahedral(stored.xy, GBUFFER_NORMAL_OCT);
#endif
}

// [decode-gbuffer]
// One sample of a pixel; `at` is where in the window it lies (the pixel centre, or a sample's
// own position: vec2(pixel) + gl_SamplePosition).
Surface decode_gbuffer_sample(ivec2 pixel, int sample_index, vec2 at) {
  Surface s;
  vec4 albedo = GB_FETCH(gb_albedo, pixel, sample_index);
  vec4 specular = GB_FETCH(gb_specular, pixel, sample_index);
  vec4 normal = GB_FETCH(gb_normal, pixel, sample_index);
  s.depth = GB_FETCH(gb_depth, pixel, sample_index).r;
  // [sky-test]
#ifdef GBUFFER_CONTROL_BITS
  s.is_sky = normal.a < 0.5;  // the control value: 0 where the clear left it, 1 under geometry
#else
  s.is_sky = s.depth == gb_depth_info.z;  // the depth buffer still holds its clear value
#endif
  // [/sky-test]
  s.position = reconstruct_position(at, s.is_sky ? gb_depth_info.z : s.depth);
#ifdef GBUFFER_STORED_POSITION
  if (!s.is_sky) s.position = GB_FETCH(gb_position, pixel, sample_index).xyz;
#endif
  if (s.is_sky) {  // defined values, never NaN: nothing here is lit
    s.normal = vec3(0.0);
    s.albedo = s.specular = s.emissive = vec3(0.0);
    s.exponent = 1.0;
    return s;
  }
  s.normal = decode_normal(normal);
  s.albedo = albedo.rgb;
  s.specular = specular.rgb;
#ifdef GBUFFER_FLOAT_EXPONENT
  s.exponent = specular.a;
#else
  s.exponent = decode_exponent(specular.a);
#endif
#ifdef GBUFFER_EMISSIVE_ALBEDO_SCALE
  s.emissive = albedo.rgb * albedo.a;  // the source: a strength that tints with the albedo
#else
  s.emissive = gb_emissive[int(round(albedo.a * 255.0))].rgb;
#endif
  return s;
}

// The pixel: its (first) sample, at its centre.
Surface decode_gbuffer(ivec2 pixel) { return decode_gbuffer_sample(pixel, 0, vec2(pixel) + 0.5); }

Surface decode_gbuffer(vec2 uv) {
  return decode_gbuffer(ivec2(clamp(floor(uv * gb_size.xy), vec2(0.0), gb_size.xy - 1.0)));
}
// [/decode-gbuffer]
