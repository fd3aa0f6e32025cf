#version 450
// One local light at one surface of the MSAA frame, drawn as chapter 03's light volume
// (volume.vert places it and hands the light on): chapter 03's local_light() at the pixel's
// surface (PER_SAMPLE off: the unmarked pixels, once per pixel) or at each sample's
// (PER_SAMPLE on: the marked ones), added into the radiance with chapter 03's composite
// distributed over the lights: albedo * L1 + L2 for this light's share. Early fragment tests:
// the stencil mask decides before the shader runs, so GL_SAMPLES_PASSED counts shaded samples.
#include "10_frame/shaders/msaa_surface.glsl"

layout(early_fragment_tests) in;

flat in vec4 v_position_type;
flat in vec4 v_direction_range;
flat in vec4 v_radiance;
flat in vec4 v_spot;
flat in float v_cut;
flat in int v_light_index;  // in light order

out vec4 out_radiance;

void main() {
  // [volume-light]
  GpuLight light = GpuLight(v_position_type, v_direction_range, v_radiance, v_spot);
  Surface s = msaa_surface(ivec2(gl_FragCoord.xy));
  vec3 diffuse, specular;
  local_light(light, v_cut, v_light_index, s, diffuse, specular);  // chapter 03's, as its volumes
  out_radiance = vec4(s.albedo * diffuse + s.specular * specular, 0.0);  // blended: added
  // [/volume-light]
}
