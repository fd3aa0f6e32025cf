// Exercise 1 of chapter 05: Reinhard's extended curve, with a white point.
// `./run 05 --mode reinhard-extended --exercise 1` tonemaps with this function; add `--check`.
//
// x is the exposed radiance (per channel). Plain Reinhard, x / (1 + x), never reaches 1.
// The extended curve x (1 + x / white^2) / (1 + x) reaches exactly 1 at x = white; return
// it, no more than 1 (past the white point the curve would rise above it).
vec3 reinhard_extended(vec3 x, float white) {
  return min(x, vec3(1.0));  // no curve, a clamp at 1: write the extended curve
}
