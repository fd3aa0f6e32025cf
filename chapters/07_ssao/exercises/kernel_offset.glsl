// Exercise 2 of chapter 07: placing the classic kernel's points.
// `./run 07 --exercise 2 --show ao` computes the AO with this function; add `--check`.
//
// p is the pixel's point in view space (the camera looks down -z); `offset` is a kernel
// point in the surface's tangent frame turned into world space (t, b, n are world vectors).
// Return the point at radius * offset from p, in view space: a world direction needs the
// view matrix's rotation, mat3(u_view), before it is added to a view-space point (a
// widespread tutorial adds it unturned, and its AO then changes as the camera turns).
vec3 kernel_point(vec3 p, vec3 offset, float radius) {
  return p;  // exercise 2: place the kernel point here
}
