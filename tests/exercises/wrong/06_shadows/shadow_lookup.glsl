// A plausible wrong answer to chapter 06's exercise 1 (tests/06_shadows.cmake: it must fail):
// a constant bias alone, no normal offset and no slope term, which leaves acne where the sun grazes.
vec3 shadow_lookup(Surface s, vec3 to_light) {
  vec4 clip = sh_map.matrix * vec4(s.position, 1.0);
  vec3 window = clip.xyz / clip.w * 0.5 + 0.5;
  return vec3(window.xy, window.z - sh_map.texel_metres * sh.constant_bias / sh.depth_range);
}
