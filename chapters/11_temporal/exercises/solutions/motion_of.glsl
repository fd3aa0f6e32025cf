// Exercise 1 of chapter 11, solved: the same function as 11_temporal/shaders/motion.glsl.
vec4 motion_of(vec4 clip_now, vec4 clip_then) {
  vec2 uv_now = clip_now.xy / clip_now.w * 0.5 + 0.5;
  vec2 uv_then = clip_then.xy / clip_then.w * 0.5 + 0.5;
  return vec4(uv_now - uv_then, clip_then.w, clip_now.w);
}
