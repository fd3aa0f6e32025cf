// Exercise 1 of chapter 07: the classic estimate's range check.
// `./run 07 --exercise 1 --show ao` computes the AO with this function; add `--check`.
//
// A kernel point counts as hidden when the depth buffer holds a surface in front of it. But
// a column standing far in front of a distant wall hides the wall's kernel points too, and
// darkens a halo around itself. Fade each occluder by how far in front of the pixel it is:
// `gap` is the view depth of the pixel less that of the stored surface, and the weight is
// smoothstep(0, 1, radius / |gap|) (|gap| kept above 1e-6): 1 for an occluder within the
// radius, falling towards 0 beyond it. The chapter multiplies each hidden point by it
// (07_ssao/shaders/ssao.comp, classic_hidden).
float range_weight(float radius, float gap) {
  return 1.0;  // exercise 1: write the range check here
}
