// One surface point's motion from its clip positions now and in the last frame (both without
// jitter): the change of its uv, and its view depths (a perspective clip w is the distance
// along the view axis). Shared by the camera pass and the object pass.
// With --exercise 1 the reader's motion_of (chapters/11_temporal/exercises/) stands in.
#ifdef EXERCISE_MOTION_OF
#include EXERCISE_MOTION_OF
#else
// [motion-of]
vec4 motion_of(vec4 clip_now, vec4 clip_then) {
  vec2 uv_now = clip_now.xy / clip_now.w * 0.5 + 0.5;
  vec2 uv_then = clip_then.xy / clip_then.w * 0.5 + 0.5;
  return vec4(uv_now - uv_then, clip_then.w, clip_now.w);
}
// [/motion-of]
#endif
