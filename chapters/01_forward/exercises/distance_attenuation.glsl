// Exercise 2 of chapter 01: how a point light's radiance falls with distance.
// `./run 01 --exercise 2` lights the scene with this function; add `--check` to compare.
//
// Return the inverse square 1 / d^2 (d^2 kept above 1e-4, so a surface at the light stays
// finite), times glTF's range window when range > 0: (clamp(1 - (d / range)^4, 0, 1))^2,
// which ends the light at its range without a visible edge.
float distance_attenuation(float distance, float range) {
  return 1.0;  // no falloff at all: write the inverse square and the window
}
