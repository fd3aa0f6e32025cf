// A plausible wrong answer to chapter 11's exercise 2 (tests/11_temporal.cmake: it must fail):
// a clamp per axis, which keeps the history inside the box but moves its hue off the line
// towards the box's centre.
vec3 clip_to_box(vec3 lo, vec3 hi, vec3 q) {
  return clamp(q, lo, hi);
}
