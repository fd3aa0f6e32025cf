// Exercise 3 of chapter 08: the surface a sample stands for.
// `./run 08 --show indirect --exercise 3` gathers with this function; add `--check` to compare.
//
// Each sample is an equal `share` of the disk's area as seen at the receiver's view depth zr.
// At the emitter e (view depth ze = view_depth(e)) the same pixels cover (ze / zr)^2 times as
// much, and a surface seen at a slant more still: divide by |ne . (direction from e to the
// eye, gb_eye.xyz)|, kept at least 0.2 so a grazing surface does not blow up.
float sample_area(float share, float zr, vec3 e, vec3 ne) {
  return share;  // as if every emitter were at the receiver's depth, facing the eye: write the area
}
