// Exercise 1 of chapter 08: the light one disk sends to a point (the disk-to-disk transfer).
// `./run 08 --show indirect --exercise 1` gathers with this function; add `--check` to compare.
//
// The emitter is a small disk of area `area` at e with unit normal ne; the receiver is the
// point p with unit normal np. With v the unit direction from p to e and r2 the squared
// distance, the fraction of the emitter's light that reaches p is the disk's form factor
//     area * max(-ne.v, 0) * max(np.v, 0) / (pi r2 + area)
// (the emitter faces the receiver, the receiver faces the emitter; the + area keeps a close
// disk finite). Return 0 when r2 <= 0 or area <= 0.
float disk_transfer(vec3 p, vec3 np, vec3 e, vec3 ne, float area) {
  return 0.0;  // no light passes: write the transfer
}
