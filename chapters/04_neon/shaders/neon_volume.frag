#version 450
// One tube at one pixel of its capsule: the surface from chapter 02's G-buffer, the tube from
// capsule.vert (the instance's packed NeonGpu, flat), chapter 04's neon_light(), added into
// chapter 03's light buffer (L1 diffuse, L2 specular), as chapter 03's light.frag does for a
// point light. Only the pixels the stencil mask lets through get here.
#include "04_neon/shaders/neon.glsl"
#include "02_gbuffer/shaders/gbuffer.glsl"

// Depth and stencil tests before the shader: what the mask rejects is never shaded, and
// GL_SAMPLES_PASSED counts exactly the fragments shaded.
layout(early_fragment_tests) in;

flat in mat4 v_packed;
flat in vec4 v_barn_doors;
flat in vec4 v_extra;

uniform int u_method;   // NEON_* in neon.glsl
uniform int u_samples;  // ground truth: samples per tube; points: point lights per tube

#ifdef COUNT_FRAGMENTS
// [count]
// Exact counts for the tests and the panel: every invocation is a fragment shaded; it is
// lit when the tube adds anything at all to it; lit_open asks the same with the barn doors
// open, to tell what the capsule wastes from what the doors take away. 64-bit, chapter 03's
// counters, from this tube's first (u_counter_base); counter 3 is the marking draws'.
#include "03_light_volumes/shaders/fragment_counters.glsl"
const uint kCountShaded = 0u, kCountLit = 1u, kCountLitOpen = 2u;
// [/count]
#endif

layout(location = 0) out vec4 out_diffuse;   // L1: light for the albedo to reflect
layout(location = 1) out vec4 out_specular;  // L2: light reflected by the specular colour

void main() {
  Surface s = decode_gbuffer(ivec2(gl_FragCoord.xy));
  NeonGpu tube = NeonGpu(v_packed, v_barn_doors, v_extra);
  NeonMethod method = NeonMethod(u_method, u_samples);
  NeonResult r = NeonResult(vec3(0.0), vec3(0.0));
  // [neon-pixel]
  // The surface as chapter 04's functions want it, rebuilt from chapter 02's Surface; the
  // tube's own volume mask (capsule or cylinder) still applies inside neon_light(), so the
  // capsule mesh may be a little larger than the light without lighting more.
  NeonSurface surface = NeonSurface(s.position, s.normal, normalize(gb_eye.xyz - s.position), s.exponent);
  if (!s.is_sky) r = neon_light(surface, tube, method);
  // [/neon-pixel]
#if defined(COUNT_FRAGMENTS) || defined(SHOW_WASTE)
  bool lit = any(greaterThan(r.diffuse + r.specular, vec3(0.0))), lit_open = lit;
  if (!lit && !s.is_sky && tube.barn_doors.y > 0.0) {
    NeonGpu open_tube = tube;
    open_tube.barn_doors.y = 0.0;  // no doors
    NeonResult o = neon_light(surface, open_tube, method);
    lit_open = any(greaterThan(o.diffuse + o.specular, vec3(0.0)));
  }
#endif
#ifdef COUNT_FRAGMENTS
  count_fragment(kCountShaded);
  if (lit) count_fragment(kCountLit);
  if (lit_open) count_fragment(kCountLitOpen);
#endif
#ifdef SHOW_WASTE
  // The picture of what each capsule shades, summed over the tubes: green where its tube
  // lights the pixel, red where it does not (the surface faces away, or lies beyond the round
  // capsule), blue where only the barn doors keep the light off.
  out_diffuse = vec4(lit ? vec3(0.0, 0.2, 0.0) : lit_open ? vec3(0.0, 0.1, 0.7) : vec3(0.7, 0.0, 0.0), 0.0);
  out_specular = vec4(0.0);
#else
  out_diffuse = vec4(r.diffuse, 0.0);
  out_specular = vec4(s.specular * r.specular, 0.0);
#endif
}
