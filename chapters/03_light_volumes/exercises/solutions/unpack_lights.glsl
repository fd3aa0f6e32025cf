// Exercise 3 of chapter 03, solved: the same functions as 03_light_volumes/shaders/light_instance.glsl.
GpuLight unpack_point(vec4 position_radius, vec4 radiance_range) {
  return GpuLight(vec4(position_radius.xyz, LIGHT_POINT), vec4(0.0, 0.0, -1.0, radiance_range.w),
                  vec4(radiance_range.rgb, 0.0), vec4(0.0));
}

GpuLight unpack_spot(vec4 position_radius, vec4 radiance_range, vec4 direction_cone) {
  return GpuLight(vec4(position_radius.xyz, LIGHT_SPOT), vec4(octahedral_unfold(direction_cone.xy), radiance_range.w),
                  vec4(radiance_range.rgb, 0.0), vec4(direction_cone.zw, 0.0, 0.0));
}
