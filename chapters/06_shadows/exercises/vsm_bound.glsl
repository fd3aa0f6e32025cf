// Exercise 2 of chapter 06: variance shadow maps, Chebyshev's bound.
// `./run 06 --exercise 2 --mode vsm` shadows the atrium with this function; add `--check`.
//
// The filtered map holds, around the lookup, the mean of the blockers' depths m.x = E[z] and
// of their squares m.y = E[z^2]. The fraction of them at least as far as the receiver's depth
// d is at most p_max = variance / (variance + (d - m.x)^2) (Chebyshev's one-sided inequality),
// with variance = E[z^2] - E[z]^2, kept at least sh.min_variance (rounding can make it 0 or
// negative). Return 1 where d <= m.x (in front of the mean: lit). Where two blockers overlap,
// p_max stays above 0 inside the shadow (light bleeding): treat p_max below sh.vsm_p_min as
// shadow and rescale the rest to [0, 1], clamp((p_max - p_min) / (1 - p_min), 0, 1).
float vsm_visibility(vec2 m, float d) {
  return 1.0;  // lit everywhere: write the bound
}
