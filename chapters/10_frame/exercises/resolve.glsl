// Exercise 3 of chapter 10: MSAA's resolve, after the tone curve.
// `./run 10 --msaa 4 --exercise 3` resolves with this pass; add `--check` to compare.
//
// Write the pixel's colour from its MSAA_SAMPLES samples of light (texelFetch(u_radiance,
// pixel, i) when MSAA_SAMPLES > 1; one plain texel otherwise): tonemap each sample with
// display() and average the results, which is what the eye should see blended at an edge.
// With u_resolve_first (--msaa-view resolve-first, the way the source warns against),
// average the light first and tonemap the mean once.
void main() {
  // sample 0 alone (and no resolve-first): write the resolve
  out_color = vec4(display(texelFetch(u_radiance, ivec2(gl_FragCoord.xy), 0).rgb), 1.0);
}
