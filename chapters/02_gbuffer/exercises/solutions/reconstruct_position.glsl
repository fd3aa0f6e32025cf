// Exercise 3 of chapter 02, solved: the same function as 02_gbuffer/shaders/gbuffer.glsl.
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
