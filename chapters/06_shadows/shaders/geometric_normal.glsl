// The receiver's geometric normal, for the three things in the hook that ask where the surface
// lies rather than how it shades: the slope-scaled bias, the normal offset and PCF's receiver
// plane. A normal map tilts the shading normal by its bumps; the depth the G-buffer stores does
// not, so the plane is rebuilt from the depth of the pixel's neighbours (chapter 02's
// reconstruct_position). No G-buffer channel is added: every layout has a depth.
// [geometric-normal-glsl]
// A pixel's point, as decode_gbuffer reconstructs (or, in the float layout, stores) it.
vec3 gbuffer_point(ivec2 p) {
#ifdef GBUFFER_STORED_POSITION
  return GB_FETCH(gb_position, p, 0).xyz;
#elif defined(GBUFFER_SAMPLES)
  // Chapter 10's MSAA: the pixel's centre, where its per-pixel light pass puts the surface
  // (msaa_surface.glsl: the mean of the samples' depths), so the plane is the one it lights.
  float depth = 0.0;
  for (int i = 0; i < GBUFFER_SAMPLES; ++i) depth += GB_FETCH(gb_depth, p, i).r;
  return reconstruct_position(vec2(p) + 0.5, depth / float(GBUFFER_SAMPLES));
#else
  return reconstruct_position(vec2(p) + 0.5, GB_FETCH(gb_depth, p, 0).r);
#endif
}
// The step to the neighbour `d` pixels away that lies on the same surface: of the two
// neighbours on that axis, the one whose step runs flatter to the shading normal's plane. A pixel
// at a crease does not step onto the other face (that step climbs the other face, steeply to
// this one's normal, which a normal map tilts by far less), nor, mostly, one at a silhouette
// across the gap to what lies behind it or in front (that step runs along the view ray, into the
// surface). Mostly: a bump that tilts the normal map towards the view ray makes the gap's step
// the flatter one. So a side across a gap is left out first. Window depth is affine across a
// plane's pixels: its steps are equal on both sides and its second difference D(p) - 2 D(p + d)
// + D(p + 2d) is the depth's rounding; across a gap both are the jump. A side is a gap when its
// step and its second difference each exceed four of the other side's steps and 1e-6 (16 steps
// of a 24-bit depth: above the rounding where the surface faces the camera and its steps are
// nearly 0). A crease bends the depth but does not jump it: the flatter step decides there.
float depth_at(ivec2 p) { return GB_FETCH(gb_depth, p, 0).r; }
bool across_a_gap(ivec2 p, ivec2 d, float z, float other_step) {
  float limit = max(4.0 * other_step, 1e-6), next = depth_at(p + d);
  return abs(next - z) > limit && abs(z - 2.0 * next + depth_at(p + 2 * d)) > limit;
}
vec3 surface_step(ivec2 p, ivec2 d, vec3 centre, vec3 shading) {
  ivec2 size = ivec2(gb_size.xy);
  bool has_ahead = all(lessThan(p + d, size)), has_behind = all(greaterThanEqual(p - d, ivec2(0)));
  vec3 ahead = has_ahead ? gbuffer_point(p + d) - centre : vec3(0.0);
  vec3 behind = has_behind ? centre - gbuffer_point(p - d) : vec3(0.0);
  // At the image's border only one neighbour is there.
  bool flatter = abs(dot(ahead, shading)) * length(behind) < abs(dot(behind, shading)) * length(ahead);
  if (all(lessThan(p + 2 * d, size)) && all(greaterThanEqual(p - 2 * d, ivec2(0)))) {
    float z = depth_at(p);
    bool ahead_gap = across_a_gap(p, d, z, abs(z - depth_at(p - d)));
    bool behind_gap = across_a_gap(p, -d, z, abs(depth_at(p + d) - z));
    if (ahead_gap != behind_gap) flatter = behind_gap;
  }
  return !has_behind || (has_ahead && flatter) ? ahead : behind;
}
vec3 geometric_normal(Surface s) {
  ivec2 p = ivec2(frame_pixel());
  // A forward pass (the glass, chapter 08's back faces) lights its own fragment, not the
  // G-buffer's pixel: its interpolated normal is already the geometry's, less the normal map.
  if (GB_FETCH(gb_depth, p, 0).r != s.depth) return s.normal;
  vec3 n = cross(surface_step(p, ivec2(1, 0), s.position, s.normal), surface_step(p, ivec2(0, 1), s.position, s.normal));
  if (!(dot(n, n) > 0.0)) return s.normal;  // a pixel-wide object at the image's border
  n = normalize(n);
  n = dot(n, gb_eye.xyz - s.position) < 0.0 ? -n : n;  // towards the camera, as the surface seen
  // Both neighbours on an axis off the surface (an object a pixel wide): the plane is another
  // surface's. No normal map tilts as far as a right angle.
  return dot(n, s.normal) > 0.0 ? n : s.normal;
}
// [/geometric-normal-glsl]
