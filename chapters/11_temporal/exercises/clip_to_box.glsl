// Exercise 2 of chapter 11: holding the history to this frame's neighbourhood.
// `./run 11 --exercise 2 --path walk` resolves with this function; add `--check`.
//
// Where the history shows a surface this pixel no longer sees, its colour lies outside the box
// [lo, hi] of this frame's 3x3 neighbourhood (in YCoCg): a ghost. Return q moved towards the
// box's centre c = (lo + hi) / 2 along the line from c until it lies inside: with e the box's
// half extent (hi - lo) / 2 and v = q - c, the largest of |v / e| over the three axes says how
// far outside q is (above 1: outside); divide v by it. Inside, return q as it is. (A clamp per
// axis would also keep q inside, but moves its hue: the line keeps it.)
vec3 clip_to_box(vec3 lo, vec3 hi, vec3 q) {
  return q;  // the history as it is: write the clip
}
