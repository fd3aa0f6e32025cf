// Exercise 3 of chapter 04: the point of the tube nearest a point.
// `./run 04 --exercise 3` shades with this function; add `--check` to compare.
//
// Return the parameter, in [0, 1] along the segment from a to b, of the point of the segment
// nearest to p: the projection of p - a onto b - a, divided by |b - a|^2, clamped to [0, 1].
// A segment of (almost) no length (|b - a|^2 < 1e-20): return 0. The capsule volumes' mask,
// the barn doors and the source's method all measure distance to the tube with it.
float neon_closest_on_segment(vec3 p, vec3 a, vec3 b) {
  return 0.0;  // always the start of the tube: write the projection
}
