// Reading a quantity's history where this pixel's surface was last frame, shared by the
// accumulations (ao_accumulate.comp, gi_accumulate.comp). Needs disocclusion.glsl first (the
// motion targets and the test).

// [history-lost]
// Where this pixel's surface was last frame (uv_then), and whether its history is lost: a reset
// (a cut), outside the last image, or hidden there (disocclusion.glsl's test).
bool history_lost(ivec2 p, ivec2 size, vec4 own, bool reset, out vec2 uv_then, out float slack) {
  uv_then = (vec2(p) + 0.5) / vec2(size) - own.xy;
  slack = depth_slack(p, size, own.z);
  if (reset || any(lessThan(uv_then, vec2(0.0))) || any(greaterThan(uv_then, vec2(1.0)))) return true;
  return disoccluded(uv_then, own.z, slack);
}
// [/history-lost]

// [history-footprint]
// The bilinear footprint around uv_then: its four texels q[k], each weighed w[k] by its
// bilinear weight if its last depth is this surface's, by 0 if not (a bilinear read across an
// edge would bring in the other surface's history). Returns the weights' sum.
float history_footprint(vec2 uv_then, ivec2 size, float depth_then, float slack, out ivec2 q[4], out float w[4]) {
  vec2 pos = uv_then * vec2(size) - 0.5;
  ivec2 base = ivec2(floor(pos));
  vec2 f = pos - vec2(base);
  float weights = 0.0;
  for (int j = 0; j <= 1; ++j)
    for (int i = 0; i <= 1; ++i) {
      int k = j * 2 + i;
      q[k] = clamp(base + ivec2(i, j), ivec2(0), size - 1);
      float b = (i == 1 ? f.x : 1.0 - f.x) * (j == 1 ? f.y : 1.0 - f.y);
      bool same = abs(texelFetch(u_previous_motion, q[k], 0).w - depth_then) <= u_depth_tolerance * depth_then + slack;
      w[k] = same && b > 0.0 ? b : 0.0;
      weights += w[k];
    }
  return weights;
}
// [/history-footprint]
