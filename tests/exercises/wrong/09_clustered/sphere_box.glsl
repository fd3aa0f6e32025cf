// A plausible wrong answer to chapter 09's exercise 3 (tests/09_clustered.cmake: it must fail):
// the squared distance compared with the radius, not with its square.
bool sphere_meets_box(vec3 centre, float radius, Box box) {
  vec3 d = centre - clamp(centre, box.lo, box.hi);
  return dot(d, d) <= radius;
}
