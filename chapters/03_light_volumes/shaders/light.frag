#version 450
// One light at one pixel: the surface from the G-buffer, chapter 01's light_incident() and
// blinn_phong(), added into the light buffer (diffuse and specular apart). Every strategy
// runs this same shader; they differ only in which pixels reach it.
#include "01_forward/shaders/lighting.glsl"
#include "02_gbuffer/shaders/gbuffer.glsl"
#include FRAME_VISIBILITY  // hooks/full_visibility.glsl, or a later chapter's (shadows)
#include "03_light_volumes/shaders/local_light.glsl"

// Depth and stencil tests before the shader, so what the stencil mask rejects is never
// shaded (and GL_SAMPLES_PASSED counts shaded fragments).
layout(early_fragment_tests) in;

flat in vec4 v_position_type;
flat in vec4 v_direction_range;
flat in vec4 v_radiance;
flat in vec4 v_spot;
flat in float v_cut;
flat in int v_light_index;  // in light order

#ifdef COUNT_FRAGMENTS
// [count]
// Exact counts for the tests and the panel, 64-bit (fragment_counters.glsl): every invocation
// is a fragment shaded; it is lit when the light adds anything at all to it. (The third count
// leaves out the last 1% of the radius, where a depth test may meet a volume's face within the
// depth buffer's precision: there the volumes may miss a fragment the full-screen pass lights,
// by at most the cut threshold.) Counter 3 is stencil.frag's: the marking draws' fragments.
#include "03_light_volumes/shaders/fragment_counters.glsl"
const uint kCountShaded = 0u, kCountLit = 1u, kCountLitInner = 2u;
// [/count]
#endif

#if defined(LIGHT_PREPASS)
layout(location = 0) out vec4 out_light;     // rgb: diffuse light, a: specular as one number
#else
layout(location = 0) out vec4 out_diffuse;   // L1: light for the albedo to reflect
layout(location = 1) out vec4 out_specular;  // L2: light reflected by the specular colour
#endif

void main() {
  GpuLight light = GpuLight(v_position_type, v_direction_range, v_radiance, v_spot);
  Surface s = decode_gbuffer(ivec2(gl_FragCoord.xy));
  vec3 diffuse, specular;
  local_light(light, v_cut, v_light_index, s, diffuse, specular);  // local_light.glsl
  bool lit = any(greaterThan(diffuse + specular, vec3(0.0)));
#ifdef COUNT_FRAGMENTS
  count_fragment(kCountShaded);
  if (lit) count_fragment(kCountLit);
  if (lit && distance(light.position_type.xyz, s.position) <= 0.99 * v_cut) count_fragment(kCountLitInner);
#endif
#if defined(HEAT_SHADED)
  out_diffuse = vec4(1.0);  // fragments shaded per pixel, summed by the blending
  out_specular = vec4(0.0);
#elif defined(HEAT_LIT)
  out_diffuse = vec4(lit ? 1.0 : 0.0);
  out_specular = vec4(0.0);
#elif defined(LIGHT_PREPASS)
  // [prepass-light]
  // Deferred lighting keeps one number for the specular light: the G-buffer has no specular
  // colour to tint it with, and one RGBA target has one channel left.
  out_light = vec4(diffuse, dot(specular, vec3(0.2126, 0.7152, 0.0722)));
  // [/prepass-light]
#else
  out_diffuse = vec4(diffuse, 0.0);
  out_specular = vec4(s.specular * specular, 0.0);
#endif
}
