#version 450
// The edge pass: one fragment per pixel compares the pixel's samples in the multisampled
// G-buffer and, where they differ, survives to write 1 into the stencil (glStencilOp REPLACE
// on every covered sample); elsewhere it is discarded and the stencil keeps its 0. No early
// fragment tests here: with them the stencil would be written before the discard.
#include "02_gbuffer/shaders/gbuffer.glsl"

uniform float u_depth_threshold;  // distance off the plane, relative to the distance to the eye
uniform float u_cos_normal;       // cos of the largest angle between normals
uniform bool u_mark_all;          // the cross-check: every pixel is an edge
uniform vec2 u_sample_positions[MSAA_SAMPLES];  // within the pixel, glGetMultisamplefv

// Exercise 2 (chapters/10_frame/exercises/edge_test.glsl) stands in for it.
#ifdef EXERCISE_EDGE_TEST
#include EXERCISE_EDGE_TEST
#else
void main() {
  // [edge-test]
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  Surface first = decode_gbuffer_sample(pixel, 0, vec2(pixel) + u_sample_positions[0]);
  float first_distance = distance(gb_eye.xyz, first.position);
  bool edge = u_mark_all;
  for (int i = 1; i < MSAA_SAMPLES && !edge; ++i) {
    Surface s = decode_gbuffer_sample(pixel, i, vec2(pixel) + u_sample_positions[i]);
    if (s.is_sky != first.is_sky) {
      edge = true;  // geometry against the sky
    } else if (!s.is_sky) {
      // Off each other's plane (not merely at another depth: a floor seen at a grazing angle
      // changes depth fast across a pixel, yet its samples lie in one plane), or turned.
      vec3 d = s.position - first.position;
      float off_plane = max(abs(dot(first.normal, d)), abs(dot(s.normal, d)));
      // Or another emissive material (a palette code per material: exact): a lit window in
      // the plane of its wall is an edge that neither depth nor normal sees.
      edge = off_plane > u_depth_threshold * first_distance || dot(s.normal, first.normal) < u_cos_normal ||
             s.emissive != first.emissive;
    }
  }
  if (!edge) discard;
  // [/edge-test]
}
#endif
