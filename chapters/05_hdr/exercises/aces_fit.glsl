// Exercise 2 of chapter 05: the ACES filmic curve, as Narkowicz's rational fit.
// `./run 05 --mode aces --exercise 2` tonemaps with this function; add `--check` to compare.
//
// Return (x (a x + b)) / (x (c x + d) + e), clamped to [0, 1], with Narkowicz's (2015)
// constants a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14. (Why this shape: a toe that
// darkens the shadows a little, a shoulder that rolls the highlights off to white.)
vec3 aces_fit(vec3 x) {
  return min(x, vec3(1.0));  // no curve, a clamp at 1: write the fit
}
