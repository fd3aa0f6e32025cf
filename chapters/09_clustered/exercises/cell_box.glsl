// Exercise 2 of chapter 09: the box around one cell.
// `./run 09 --exercise 2 --lights 1000 --show heat-evaluated` culls with this box; add `--check`.
//
// A cell is the piece of the view frustum behind the pixels [p0, p1) between the view depths
// d0 and d1. Return the axis-aligned box, in view space, around its eight corners: for each
// corner pixel (x from p0.x or p1.x, y from p0.y or p1.y) at each depth d (d0 or d1),
//   ndc = pixel / u_grid.xy * 2 - 1, and the view-space point on that pixel's ray at depth d is
//   (d * (ndc.x + P20) / P00, d * (ndc.y + P21) / P11, -d),
// with u_projection = (P00, P11, P20, P21) (the camera looks down -z). Widen the depths first
// by the relative pad kDepthPad (d0 * (1 - kDepthPad), d1 * (1 + kDepthPad)): rounding must not
// lose a light that just touches the cell.
Box cell_box(ivec2 p0, ivec2 p1, float d0, float d1) {
  // The whole space: every light meets every cell, so the image is right and every pixel
  // evaluates every light (--show heat-evaluated). Write the cell's box.
  return Box(vec3(-1e30), vec3(1e30));
}
