// Exercise 1 of chapter 03: the window that ends a light at its range.
// `./run 03 --exercise 1` lights the street with this function; add `--check` to compare.
//
// glTF multiplies a point or spot light's inverse square by a window that is 1 at the light
// and falls smoothly to 0 at its range: with ratio = distance / range,
// window = clamp(1 - ratio^4, 0, 1)^2. Without a range (range <= 0) it is 1 everywhere.
// The volumes are cut where the windowed light fades below one output step
// (light_radius.h); inside them, this function decides how the light fades.
float range_window(float distance, float range) {
  return 1.0;  // no window: each light at full strength up to its volume's edge
}
