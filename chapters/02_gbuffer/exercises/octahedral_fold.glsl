// Exercise 1 of chapter 02: the octahedral encoding of a unit normal.
// `./run 02 --exercise 1` stores normals with this function; add `--check` to compare.
//
// Project n onto the octahedron |x| + |y| + |z| = 1 (divide by that sum) and keep x, y: that
// is the upper half (n.z >= 0). Fold the lower half (n.z < 0) over the diagonals into the
// corners: p = (1 - |p.yx|) * sign(p), with the sign of 0 taken as +1 (gb_sign_not_zero(p)).
// The result lies in [-1, 1]^2; encode_octahedral() quantises it.
vec2 octahedral_fold(vec3 n) {
  return vec2(0.0);  // every normal stored as straight up (+z): write the fold
}
