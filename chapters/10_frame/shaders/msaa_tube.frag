#version 450
// One of chapter 04's tubes at one surface of the MSAA frame, drawn as its capsule
// (04_neon/shaders/capsule.vert, the tube handed on flat): chapter 04's neon_light() at the
// pixel's surface (PER_SAMPLE off: the unmarked pixels, once per pixel) or at each sample's
// (PER_SAMPLE on: the marked ones), added into the radiance with chapter 03's composite
// distributed over the lights, as msaa_volume.frag adds a point light.
#include "04_neon/shaders/neon.glsl"
#include "10_frame/shaders/msaa_surface.glsl"

layout(early_fragment_tests) in;

flat in mat4 v_packed;
flat in vec4 v_barn_doors;
flat in vec4 v_extra;

uniform int u_method;   // NEON_* in neon.glsl
uniform int u_samples;  // ground truth: samples per tube; points: point lights per tube

out vec4 out_radiance;

void main() {
  // [tube-light]
  Surface s = msaa_surface(ivec2(gl_FragCoord.xy));
  NeonGpu tube = NeonGpu(v_packed, v_barn_doors, v_extra);
  NeonResult r = NeonResult(vec3(0.0), vec3(0.0));
  NeonSurface surface = NeonSurface(s.position, s.normal, normalize(gb_eye.xyz - s.position), s.exponent);
  if (!s.is_sky) r = neon_light(surface, tube, NeonMethod(u_method, u_samples));  // chapter 04's
  out_radiance = vec4(s.albedo * r.diffuse + s.specular * r.specular, 0.0);       // blended: added
  // [/tube-light]
}
