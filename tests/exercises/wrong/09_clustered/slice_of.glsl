// A plausible wrong answer to chapter 09's exercise 1 (tests/09_clustered.cmake: it must fail):
// uniform slices, where the cell boxes (slice_start) are exponential.
int slice_of(float d) {
  float t = (d - u_depth_range.x) / (u_depth_range.y - u_depth_range.x);
  return clamp(int(floor(t * float(u_tiles.z))), 0, u_tiles.z - 1);
}
