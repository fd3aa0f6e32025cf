// Exercise 3 of chapter 10: MSAA's resolve into the HDR chain's radiance.
// `./run 10 --msaa 4 --exercise 3` resolves with this pass; add `--check` to compare.
//
// Write the pixel's radiance from its MSAA_SAMPLES samples (sample_radiance(pixel, i)) for
// chapter 05's HDR chain, which tonemaps later: a mean of the samples in which each counts
// as much as the tone curve keeps of it, tone_weight(radiance) (1 / (1 + exposed luminance)),
// so that one bright sample does not fill an edge pixel. With u_resolve_first
// (--msaa-view resolve-first) every sample weighs the same.
void main() {
  // sample 0 alone: write the resolve
  out_color = vec4(sample_radiance(ivec2(gl_FragCoord.xy), 0), 1.0);
}
