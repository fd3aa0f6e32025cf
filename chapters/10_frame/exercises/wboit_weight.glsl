// Exercise 1 of chapter 10: the depth weight of weighted blended transparency.
// `./run 10 --transparency wboit --exercise 1` blends the glass with it; add `--check` to compare.
//
// Weighted blended OIT sums every layer's colour times a weight and divides by the summed
// weights: near layers must weigh more, or a far pane shows through a near one. Return
// McGuire and Bavoil's first depth weight: with a = z / 5 and b = z / 200 (z: the view
// depth, metres), alpha * clamp(10 / (1e-5 + a^2 + b^6), 1e-2, 3e3).
float wboit_weight(float z, float alpha) {
  return alpha;  // every depth the same: write the depth weight
}
