// Exercise 3 of chapter 07: the occlusion of one disk sample.
// `./run 07 --mode disk --exercise 3 --show ao` computes the AO with this function; add `--check`.
//
// Each sample stands for a small disk of area `area` at the emitter point e, facing along
// its normal ne, seen from the receiver p with normal np at distance d = |e - p|, in the
// unit direction v. The form factor of a disk seen from a point, cosine-weighted at the
// receiver, is area cos(theta_e) cos(theta_r) / (pi d^2 + area), with cos(theta_e) = |ne . v|
// (either side of a thin surface occludes) and cos(theta_r) = max(np . v, 0).
float form_factor_occlusion(vec3 p, vec3 np, vec3 e, vec3 ne, float area) {
  vec3 v = e - p;
  float d2 = dot(v, v);
  if (d2 <= 0.0 || area <= 0.0) return 0.0;
  v *= inversesqrt(d2);
  return 0.0;  // exercise 3: write the disk's form factor here
}
