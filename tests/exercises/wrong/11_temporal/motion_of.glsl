// A plausible wrong answer to chapter 11's exercise 1 (tests/11_temporal.cmake: it must fail):
// the motion the wrong way round, then minus now, so the history is read ahead of the point.
vec4 motion_of(vec4 clip_now, vec4 clip_then) {
  vec2 uv_now = clip_now.xy / clip_now.w * 0.5 + 0.5;
  vec2 uv_then = clip_then.xy / clip_then.w * 0.5 + 0.5;
  return vec4(uv_then - uv_now, clip_then.w, clip_now.w);
}
