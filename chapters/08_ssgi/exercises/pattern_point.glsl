// Exercise 2 of chapter 08: where the samples fall in the unit disk.
// `./run 08 --show indirect --pattern regular --exercise 2` gathers with this function; add `--check`.
//
// Return sample i's point in the unit disk, for the pattern u_pattern picks:
//   0, regular: a polar grid of u_rings rings and u_spokes spokes; sample i is on ring
//      i / u_spokes and spoke i % u_spokes, at angle 2 pi spoke / u_spokes and radius
//      sqrt((ring + 0.5) / u_rings) (the square root: each ring the same share of the area);
//   1, spiral: chapter 07's golden-angle spiral, angle 2.39996323 i, radius
//      sqrt((i + 0.5) / u_samples);
//   2, randomised: the spiral turned by 2 pi jitter.x, with jitter.y in place of the 0.5.
vec2 pattern_point(int i, vec2 jitter) {
  return vec2(0.0);  // every sample at the pixel itself: write the patterns
}
