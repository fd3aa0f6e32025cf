// Exercise 3 of chapter 02: the world position of a pixel from its depth.
// `./run 02 --exercise 3` lights the image with this function; add `--check` to compare.
//
// pixel_centre is in pixels, depth the depth buffer's value. Build the point in normalised
// device coordinates: x and y from the pixel centre (gb_size.zw is 1 / the size in pixels),
// z from the depth (OpenGL's default maps z/w from [-1, 1] to [0, 1]; with
// GBUFFER_REVERSED_Z defined the depth is z/w itself). Take it back to the world with
// gb_inverse_view_projection and divide by w.
vec3 reconstruct_position(vec2 pixel_centre, float depth) {
  return vec3(0.0);  // every pixel at the world's origin: write the reconstruction
}
