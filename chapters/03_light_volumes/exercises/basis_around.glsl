// Exercise 2 of chapter 03: turning a spot's cone to its direction.
// `./run 03 --exercise 2` places the cones with this function; add `--check` to compare.
//
// The unit cone's axis is +z. Return a rotation whose third column is the unit vector n and
// whose first two are unit vectors perpendicular to n and to each other (any such pair:
// the cone is round). Take care near n = (0, 0, -1), where some constructions divide by 0;
// Duff et al. (2017) give one without a branch on the axis but the sign of n.z.
mat3 basis_around(vec3 n) {
  return mat3(1.0);  // every cone points along +z: write the basis
}
