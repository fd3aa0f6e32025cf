// Exercise 3 of chapter 07: the occlusion of one disk sample.
// `./run 07 --mode disk --exercise 3 --show ao` computes the AO with this function; add `--check`.
//
// Each sample stands for a small disk of area `area` at the emitter point e, facing along
// its normal ne, at distance sqrt(d2) from the receiver in the unit direction v. The form
// factor of a disk seen from a point, cosine-weighted at the receiver, is
// area cos(theta_e) cos(theta_r) / (pi d^2 + area), with cos(theta_e) = |ne . v| (either side
// of a thin surface occludes) and cos(theta_r) = max(n . v, 0) (n: s.normal). Add it to
// `occlusion`. Only the line marked below is yours; the rest is the chapter's.
float disk_ao(ivec2 pixel, Surface s) {
  float zr = view_depth(s.position);
  // R projected at the receiver's depth, in pixels, clamped near the camera
  float scale_px = u_projection[1][1] * 0.5 * gb_size.y / zr;  // pixels per world unit at depth zr
  float radius_px = min(u_radius * scale_px, u_max_screen_radius * gb_size.y);
  float world_radius = radius_px / scale_px;
  // each sample stands for an equal share of the disk: area pi R^2 / N at the receiver's depth
  float share = PI * world_radius * world_radius / float(u_samples);
  float occlusion = 0.0;
  // The spiral turned per pixel by the 4x4 noise tile's angle (u_noise_on): the same spiral at
  // every pixel puts its samples on the same offsets everywhere, and where a sample crosses an
  // edge it does so along a whole line of pixels (bands); turned, the tile's 16 spirals
  // interleave and the 4x4 blur averages them.
  vec3 noise = u_noise[(pixel.x & 3) + 4 * (pixel.y & 3)].xyz;
  float turn = u_noise_on != 0 ? atan(noise.y, noise.x) : 0.0;
  for (int i = 0; i < u_samples; ++i) {
    float rr = sqrt((float(i) + 0.5) / float(u_samples));
    float a = 2.39996323 * float(i) + turn;
    ivec2 sp = pixel + ivec2(round(rr * radius_px * vec2(cos(a), sin(a))));
    if (sp == pixel || any(lessThan(sp, ivec2(0))) || any(greaterThanEqual(sp, ivec2(gb_size.xy)))) continue;
    float depth = texelFetch(gb_depth, sp, 0).r;
    if (sky_depth(depth)) continue;
    vec3 e = world_at(sp, depth);
    vec3 v = e - s.position;
    float d2 = dot(v, v);
    if (u_thickness > 0.0 && d2 > u_radius * u_radius) {
      // the slab behind the sample (ssao.comp [thickness]): its point nearest the receiver,
      // at most u_thickness x the radius behind the front the depth buffer holds
      vec3 away = normalize(e - gb_eye.xyz);
      e += clamp(-dot(v, away), 0.0, u_thickness * u_radius) * away;
      v = e - s.position;
      d2 = dot(v, v);
    }
    if (d2 > u_radius * u_radius || d2 <= 0.0) continue;  // beyond the rays' length R
    vec3 ne = decode_normal(texelFetch(gb_normal, sp, 0));
    float ze = view_depth(e);
    // the share at the emitter's depth, spread over the surface the pixel sees at a slant
    vec3 to_eye = normalize(gb_eye.xyz - e);
    float area = share * (ze / zr) * (ze / zr) / max(abs(dot(ne, to_eye)), 0.2);
    v *= inversesqrt(d2);
#ifdef AO_BUNNELL
    occlusion += (1.0 - inversesqrt(1.0 + area / (PI * d2))) * abs(dot(ne, v)) * clamp(4.0 * dot(s.normal, v), 0.0, 1.0);
#else
    occlusion += 0.0;  // exercise 3: write the disk's form factor here
#endif
  }
  return 1.0 - clamp(occlusion, 0.0, 1.0);
}
