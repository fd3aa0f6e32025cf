// Exercise 3 of chapter 05: the bloom's bright pass.
// `./run 05 --bloom after --exercise 3` blooms with this function; add `--check` to compare.
//
// x is an exposed colour. Only light above the threshold blooms: with y = luminance(x),
// nothing (black) when y <= threshold (or y <= 0); otherwise the colour scaled so that its
// luminance becomes y - threshold, but no more than `limit`: x * min(y - threshold, limit) / y.
// Scaling the colour, not each channel, keeps its hue.
vec3 bright_pass(vec3 x, float threshold, float limit) {
  return vec3(0.0);  // nothing blooms: write the bright pass
}
