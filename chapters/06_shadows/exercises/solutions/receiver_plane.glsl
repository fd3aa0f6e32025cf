// Exercise 3 of chapter 06, solved: lookup_math.glsl's function on shadow_visibility.glsl's block.
vec2 receiver_plane_gradient(Surface s) {
  vec3 n = mat3(sh.view) * s.normal;
  float nz = max(n.z, 0.05);  // faces the light (n.z > 0); at most 20:1 slopes
  return vec2(n.x, n.y) / nz * sh_map.extent / sh.depth_range;
}
