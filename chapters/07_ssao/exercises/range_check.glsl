// Exercise 1 of chapter 07: the classic estimate's range check.
// `./run 07 --exercise 1 --show ao` computes the AO with these functions; add `--check`.
//
// A kernel point counts as hidden when the depth buffer holds a surface in front of it. But
// a column standing far in front of a distant wall hides the wall's kernel points too, and
// darkens a halo around itself. Fade each occluder by how far in front of the pixel it is:
// with the pixel at view depth -p.z and the stored surface at `scene`,
// range = smoothstep(0, 1, radius / |(-p.z) - scene|) (the difference kept above 1e-6): 1
// for an occluder within the radius, falling towards 0 beyond it. Only the line marked
// below is yours; the rest is the chapter's.
// The fraction of the kernel's points, scaled to `radius` and rotated by the noise vector r,
// that the depth buffer hides: the classic estimate of 1 - A.
float classic_hidden(vec3 p, vec3 t, vec3 b, vec3 n, vec3 r, float radius) {
  float hidden = 0.0;
  for (int i = 0; i < u_samples; ++i) {
    vec3 k = u_kernel[i].xyz;
    if (u_noise_on != 0) k = k - 2.0 * dot(k, r) * r;  // reflect: the height above the surface stays
    vec3 offset = k.x * t + k.y * b + k.z * n;         // world space
#ifdef AO_TUTORIAL_BUG
    vec3 q = p + radius * offset;                      // the bug: a world offset on a view-space point
#else
    vec3 q = p + radius * (mat3(u_view) * offset);     // both in view space
#endif
    vec4 clip = u_projection * vec4(q, 1.0);
    if (clip.w <= 0.0) continue;
    vec2 ndc = clip.xy / clip.w;
    if (any(greaterThan(abs(ndc), vec2(1.0)))) continue;  // off the screen: nothing known, counts as open
    ivec2 sp = clamp(ivec2((ndc * 0.5 + 0.5) * gb_size.xy), ivec2(0), ivec2(gb_size.xy) - 1);
    float depth = texelFetch(gb_depth, sp, 0).r;
    if (sky_depth(depth)) continue;
    float scene = view_depth(world_at(sp, depth));  // what the depth buffer holds there
    float sample_depth = -q.z;
    // hidden when the stored surface is in front of the point; the range check fades
    // occluders far in front of the pixel (a column before a distant wall)
    float range = 1.0;  // exercise 1: write the range check here
    hidden += (scene <= sample_depth - u_bias * radius ? 1.0 : 0.0) * range;
  }
  return hidden / float(u_samples);
}
float classic_ao(ivec2 pixel, Surface s) {
  vec3 p = (u_view * vec4(s.position, 1.0)).xyz;  // view space: the camera looks down -z
  vec3 t, b;
  basis(s.normal, t, b);                           // the tangent frame, in world space
  int tile = (pixel.x & 3) + 4 * (pixel.y & 3);
  float a = 1.0 - classic_hidden(p, t, b, s.normal, u_noise[tile].xyz, u_radius);
  // The source's two radii: the same kernel at R / 5, rotated by the tile's next vector (so the
  // two sets' points do not line up), its visibility multiplying the wide one's. Within R / 5 of
  // a contact both see the occluder and A is darker than the wide radius alone; beyond R / 5
  // the narrow set sees nothing and A is the wide radius's.
  if (u_two_radii != 0) a *= 1.0 - classic_hidden(p, t, b, s.normal, u_noise[(tile + 5) & 15].xyz, 0.2 * u_radius);
  return a;
}
