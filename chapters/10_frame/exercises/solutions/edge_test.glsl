// Exercise 2 of chapter 10, solved: the same function as 10_frame/shaders/msaa_edges.frag.
void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  Surface first = decode_gbuffer_sample(pixel, 0, vec2(pixel) + u_sample_positions[0]);
  float first_distance = distance(gb_eye.xyz, first.position);
  bool edge = u_mark_all;
  for (int i = 1; i < MSAA_SAMPLES && !edge; ++i) {
    Surface s = decode_gbuffer_sample(pixel, i, vec2(pixel) + u_sample_positions[i]);
    if (s.is_sky != first.is_sky) {
      edge = true;  // geometry against the sky
    } else if (!s.is_sky) {
      // Off each other's plane (not merely at another depth: a floor seen at a grazing angle
      // changes depth fast across a pixel, yet its samples lie in one plane), or turned.
      vec3 d = s.position - first.position;
      float off_plane = max(abs(dot(first.normal, d)), abs(dot(s.normal, d)));
      // Or another emissive material (a palette code per material: exact): a lit window in
      // the plane of its wall is an edge that neither depth nor normal sees.
      edge = off_plane > u_depth_threshold * first_distance || dot(s.normal, first.normal) < u_cos_normal ||
             s.emissive != first.emissive;
    }
  }
  if (!edge) discard;
}
