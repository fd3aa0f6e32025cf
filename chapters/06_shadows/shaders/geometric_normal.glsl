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
// neighbours on that axis, the one whose step runs flatter to the shading normal's plane. A
// pixel at a silhouette does not step across the gap to what lies behind it (that step runs
// along the view ray, into the surface), nor one at a crease onto the other face (that step
// climbs the other face, steeply to this one's normal, which a normal map tilts by far less).
vec3 surface_step(ivec2 p, ivec2 d, vec3 centre, vec3 shading) {
  ivec2 size = ivec2(gb_size.xy);
  bool has_ahead = all(lessThan(p + d, size)), has_behind = all(greaterThanEqual(p - d, ivec2(0)));
  vec3 ahead = has_ahead ? gbuffer_point(p + d) - centre : vec3(0.0);
  vec3 behind = has_behind ? centre - gbuffer_point(p - d) : vec3(0.0);
  // At the image's border only one neighbour is there.
  bool flatter = abs(dot(ahead, shading)) * length(behind) < abs(dot(behind, shading)) * length(ahead);
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
