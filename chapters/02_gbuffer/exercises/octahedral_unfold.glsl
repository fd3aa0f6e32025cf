// Exercise 2 of chapter 02: decoding the octahedral normal.
// `./run 02 --exercise 2` reads normals with this function; add `--check` to compare.
//
// Undo octahedral_fold(): n = (p, 1 - |p.x| - |p.y|). Where n.z < 0 the point was folded:
// move x and y back towards the axes by t = -n.z (each keeps its sign: x -= t when x >= 0,
// x += t otherwise; the same for y). Return n normalised.
vec3 octahedral_unfold(vec2 p) {
  return vec3(0.0, 0.0, 1.0);  // every normal read as straight up (+z): write the unfold
}
