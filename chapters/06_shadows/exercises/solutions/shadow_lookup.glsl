// Exercise 1 of chapter 06, solved: the same function as 06_shadows/shaders/shadow_visibility.glsl.
vec3 shadow_lookup(Surface s, vec3 to_light) {
  float cos_theta = clamp(dot(s.normal, to_light), 1e-4, 1.0);
  float sin_theta = sqrt(1.0 - cos_theta * cos_theta);
  float tan_theta = min(sin_theta / cos_theta, 10.0);
  vec3 p = s.position + s.normal * (sh.normal_offset * sh_map.texel_metres * sin_theta);
  vec4 clip = sh_map.matrix * vec4(p, 1.0);
  vec3 window = clip.xyz / clip.w * 0.5 + 0.5;
  float bias = sh_map.texel_metres * (sh.constant_bias + sh.slope_bias * tan_theta) / sh.depth_range;
  return vec3(window.xy, window.z - bias);
}
