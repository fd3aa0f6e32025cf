// Exercise 3 of chapter 11, solved: the same function as 11_temporal/shaders/taa_resolve.frag.
bool disoccluded(vec2 uv_then, float depth_then, float slack) {
  vec2 size = vec2(textureSize(u_previous_motion, 0));
  ivec2 base = ivec2(floor(uv_then * size - 0.5));
  float nearest = 1e30;
  for (int j = 0; j <= 1; ++j)
    for (int i = 0; i <= 1; ++i) {
      ivec2 q = clamp(base + ivec2(i, j), ivec2(0), ivec2(size) - 1);
      nearest = min(nearest, abs(texelFetch(u_previous_motion, q, 0).w - depth_then));
    }
  return nearest > u_depth_tolerance * depth_then + slack;
}
