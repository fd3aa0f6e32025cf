// Exercise 1 of chapter 09, solved: the same function as 09_clustered/shaders/grid.glsl.
int slice_of(float d) {
  float t = log(max(d, u_depth_range.x) / u_depth_range.x) / log(u_depth_range.y / u_depth_range.x);
  return clamp(int(floor(t * float(u_tiles.z))), 0, u_tiles.z - 1);
}
