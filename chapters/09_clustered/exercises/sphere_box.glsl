// Exercise 3 of chapter 09: does a light reach a cell?
// `./run 09 --exercise 3 --lights 1000 --show heat-evaluated` culls with this test; add `--check`.
//
// A light reaches what lies within its cut radius of its centre (chapter 03's cut): a sphere.
// Return whether the sphere (centre in view space, radius) meets the axis-aligned box: the
// point of the box nearest the centre is the centre clamped to [box.lo, box.hi]; the sphere
// meets the box when that point lies within the radius. Grow the radius by a hair first,
// radius * (1 + 1e-5) + 1e-6, so that rounding never loses a light that grazes the box.
bool sphere_meets_box(vec3 centre, float radius, Box box) {
  return true;  // every light in every cell: right, and slow. Write the test.
}
