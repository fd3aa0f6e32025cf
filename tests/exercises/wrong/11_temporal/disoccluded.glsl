// A plausible wrong answer to chapter 11's exercise 3 (tests/11_temporal.cmake: it must fail):
// one texel (the nearest) read instead of the four of the bilinear footprint.
bool disoccluded(vec2 uv_then, float depth_then, float slack) {
  vec2 size = vec2(textureSize(u_previous_motion, 0));
  ivec2 q = clamp(ivec2(uv_then * size), ivec2(0), ivec2(size) - 1);
  return abs(texelFetch(u_previous_motion, q, 0).w - depth_then) > u_depth_tolerance * depth_then + slack;
}
