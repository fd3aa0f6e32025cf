// Exercise 1 of chapter 11: a surface point's motion vector.
// `./run 11 --exercise 1 --path walk --show motion` draws the motion with this function; add `--check`.
//
// Given the point's clip position now and in the last frame (both without jitter), return
// (the change of its uv since the last frame, its view depth then, its view depth now): the
// resolve reads the history at uv - motion.xy, where the point was. A uv is the clip position
// divided by w, times 0.5 plus 0.5; a perspective clip w is the view depth.
vec4 motion_of(vec4 clip_now, vec4 clip_then) {
  return vec4(0.0, 0.0, clip_then.w, clip_now.w);  // nothing moves: write the uv's change
}
