// Where a lookup reads, in GLSL: the twins of shadow_math.h's receiver_plane_gradient and
// choose_cascade and of spot_atlas.h's spot_atlas_uv, whose comments derive them; included by
// the lookup (shadow_visibility.glsl), which passes them its block's fields, and held to the C++
// by 06_shadows.gl.GlslTwins.ReceiverPlaneGradientMatchesItsCppTwin, CascadeChoiceMatchesItsCppTwin
// and SpotAtlasUvMatchesItsCppTwin; the sun's biases (shadow_math.h's slope_scaled_bias and
// normal_offset) by SlopeScaledBiasAndNormalOffsetMatchTheirCppTwins; cube_texel_world
// (cube_math.h's) by CubeTexelWorldMatchesItsCppTwin.

// [bias-math-glsl]
// shadow_math.h's slope_scaled_bias: the depth a tilted receiver may lie behind the map, a
// constant part and one that grows with tan(theta) (capped at 10), in texels of texel_world
// metres; cos_theta: the cosine between the receiver's normal and the way to the light.
float slope_scaled_bias(float constant_texels, float slope_texels, float cos_theta, float texel_world) {
  float c = clamp(cos_theta, 1e-4, 1.0);
  float tan_theta = min(sqrt(1.0 - c * c) / c, 10.0);
  return texel_world * (constant_texels + slope_texels * tan_theta);
}
// shadow_math.h's normal_offset: the lookup moved off the surface along its normal by `texels`
// texels, times sin(theta): nothing facing the light, most at grazing angles.
vec3 normal_offset(vec3 position, vec3 normal, float cos_theta, float texels, float texel_world) {
  float c = clamp(cos_theta, 0.0, 1.0);
  return position + normal * (texels * texel_world * sqrt(1.0 - c * c));
}
// [/bias-math-glsl]

// [receiver-plane-glsl]
// How the receiver's window depth changes per unit of the map's (u, v), from its normal in the
// light's view space (light_view: world to it). A PCF tap `o` away from the lookup compares the
// map with the receiver's plane there, q.z + dot(gradient, o), not with q.z: a tilted receiver
// no longer shadows itself in the kernel's outer taps. extent: the map's box across the light,
// metres; depth_range: its depth, metres.
vec2 receiver_plane_gradient(mat3 light_view, vec3 world_normal, vec2 extent, float depth_range) {
  vec3 n = light_view * world_normal;
  float nz = max(n.z, 0.05);  // faces the light (n.z > 0); at most 20:1 slopes
  return vec2(n.x, n.y) / nz * extent / depth_range;
}
// [/receiver-plane-glsl]

// [cascade-choice-glsl]
// The first cascade whose far split lies beyond the pixel's view depth; in the last `band` of its
// depth range, faded into the next one (next_weight). cascade -1 beyond the last: no map covers
// it. far: each cascade's far split; near: where the first begins.
struct CascadeChoice {
  int cascade;
  float next_weight;
};
CascadeChoice choose_cascade(float depth, vec4 far, float near, int count, float band) {
  for (int i = 0; i < count; ++i) {
    if (depth >= far[i]) continue;
    float fade = band * (far[i] - (i == 0 ? near : far[i - 1]));  // the band, metres
    float next = i + 1 < count && fade > 0.0 ? clamp((depth - (far[i] - fade)) / fade, 0.0, 1.0) : 0.0;
    return CascadeChoice(i, next);
  }
  return CascadeChoice(-1, 0.0);
}
// [/cascade-choice-glsl]

// [atlas-glsl]
// A tile-local (u, v) clamped to the centres of the tile's border texels, then placed in the
// tile (tile.xy: its lower-left corner in the atlas's (u, v), tile.z: its side; texels: its
// texels a side). A PCF tap past the tile's edge reads the tile's own border, never the
// neighbour's depths.
vec2 spot_atlas_uv(vec3 tile, float texels, vec2 uv) {
  float half_texel = 0.5 / texels;
  return tile.xy + clamp(uv, vec2(half_texel), vec2(1.0 - half_texel)) * tile.z;
}
// [/atlas-glsl]

// cube_math.h's cube_texel_world: a cube map texel's width at `distance` from the light on a face
// of `size` texels, 2 d / N (a face spans tan 45 = 1 each side of its centre).
float cube_texel_world(float distance, float size) { return 2.0 * distance / size; }
