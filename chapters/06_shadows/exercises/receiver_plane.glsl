// Exercise 3 of chapter 06: PCF's receiver plane.
// `./run 06 --exercise 3 --kernel 7` filters the sun's shadow with this function; add `--check`.
//
// PCF compares k x k map texels around the lookup with the receiver's depth. On a tilted
// receiver the depth at a tap `o` away (in the map's u, v) is not the lookup's: it changes by
// dot(gradient, o), and a flat comparison shadows the receiver itself in the outer taps.
// Return that gradient, the change of window depth per unit of u and v: with n the normal in
// the light's view space (mat3(sh.view) * s.normal; n.z > 0 faces the light), the plane's
// distance from the light grows by n.x / n.z metres per metre across x (and n.y / n.z across
// y), and the map's box spans sh_map.extent metres in u, v and sh.depth_range metres in depth:
// gradient = n.xy / n.z * sh_map.extent / sh.depth_range, n.z kept at least 0.05 (slopes of
// at most 20:1).
vec2 receiver_plane_gradient(Surface s) {
  return vec2(0.0);  // a flat receiver: write the plane's gradient
}
