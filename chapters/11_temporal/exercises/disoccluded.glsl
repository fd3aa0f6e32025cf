// Exercise 3 of chapter 11: was this surface hidden last frame?
// `./run 11 --exercise 3 --path walk --show rejected` marks (red) where it drops the history; add `--check`.
//
// The motion says where the surface was last frame (uv_then) and how far from the camera
// (depth_then). The last frame's view depths are u_previous_motion's w (a texture of the last
// frame's size). If none of the four texels around uv_then (the bilinear footprint:
// floor(uv_then * size - 0.5) and the three next to it, clamped to the texture) held a depth
// within u_depth_tolerance * depth_then + slack of depth_then, something else was there: return
// true, and the resolve drops the history here. (slack: how far the depth runs along this
// surface's slope over the distance to those samples; the resolve computes it.)
bool disoccluded(vec2 uv_then, float depth_then, float slack) {
  return false;  // never hidden: write the test
}
