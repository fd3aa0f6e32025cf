// Exercise 2 of chapter 10: which pixels MSAA lights per sample.
// `./run 10 --msaa 4 --msaa-view edges --exercise 2` marks edges with this pass; add `--check`.
//
// One fragment per pixel compares the pixel's samples in the multisampled G-buffer
// (decode_gbuffer_sample(pixel, i, vec2(pixel) + u_sample_positions[i]) for i < MSAA_SAMPLES)
// with sample 0, and survives where they differ (it then marks the stencil); otherwise it
// must `discard`. Samples differ when one is sky and the other not; when either lies off
// the other's plane by more than u_depth_threshold times sample 0's distance to the eye
// (max(|n0.d|, |ni.d|), d the difference of the positions); when their normals are more than
// acos(u_cos_normal) apart; or when their emissive colours differ. u_mark_all marks every
// pixel (a cross-check).
void main() {
  if (!u_mark_all) discard;  // no edges: write the test
}
