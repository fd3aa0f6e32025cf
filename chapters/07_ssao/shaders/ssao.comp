#version 450
// Chapter 07's ambient occlusion from the G-buffer, one invocation per AO texel: the classic
// algorithm (AO_CLASSIC) or the source's 2D-disk method with Bunnell's term (AO_DISK). The C++
// twin of every formula here is ao_math.h. Writes A in [0, 1], 1 where nothing occludes (and
// for the sky).
layout(local_size_x = 8, local_size_y = 8) in;
#include "02_gbuffer/shaders/gbuffer.glsl"

layout(r32f, binding = 0) uniform writeonly image2D u_out;

uniform mat4 u_view, u_projection;
uniform int u_samples;
uniform float u_radius;             // the method's radius, world units: R x AoSettings::reach
uniform float u_power;              // A is raised to it at the end (1: untuned)
uniform float u_falloff;            // GTAO: occluders fade over the last u_falloff x radius
uniform float u_thickness;          // GTAO, disk: each depth sample a slab this thick (x radius) behind it
uniform int u_scale;                // 1, 2 or 4: AO texel (x, y) stands for G-buffer pixel scale * (x, y) + scale / 2
uniform int u_noise_on;
uniform float u_bias;               // x R
uniform int u_two_radii;            // classic: 1 for the source's second kernel at R / 5
uniform float u_max_screen_radius;  // disk: at most this fraction of the image height
uniform vec4 u_kernel[128];
uniform vec4 u_noise[16];

// The formulas with C++ twins in ao_math.h, in a file of their own so that a test runs them
// against the twins (tests/unit/test_07_twins_gl.cpp): PI, basis, the noise's reflection, the
// range check, the disk's terms, the spiral and GTAO's horizon and arcs.
#include "07_ssao/shaders/ao_math.glsl"

bool sky_depth(float depth) { return depth == gb_depth_info.z; }
vec3 world_at(ivec2 pixel, float depth) { return reconstruct_position(vec2(pixel) + 0.5, depth); }
float view_depth(vec3 world) { return -(u_view * vec4(world, 1.0)).z; }

#ifdef AO_CLASSIC
// [classic]
// A kernel point in view space: `offset` is a world-space direction (the tangent frame's),
// turned by the view's rotation before it is added to the view-space point p.
// With --exercise 2 the reader's kernel_point (chapters/07_ssao/exercises/kernel_offset.glsl) stands in.
#ifdef EXERCISE_KERNEL_OFFSET
#include EXERCISE_KERNEL_OFFSET
#else
vec3 kernel_point(vec3 p, vec3 offset, float radius) {
#ifdef AO_TUTORIAL_BUG
  return p + radius * offset;                   // the bug: a world offset on a view-space point
#else
  return p + radius * (mat3(u_view) * offset);  // both in view space
#endif
}
#endif

// The fraction of the kernel's points, scaled to `radius` and rotated by the noise vector r,
// that the depth buffer hides: the classic estimate of 1 - A.
float classic_hidden(vec3 p, vec3 t, vec3 b, vec3 n, vec3 r, float radius) {
  float hidden = 0.0;
  for (int i = 0; i < u_samples; ++i) {
    vec3 k = u_kernel[i].xyz;
    if (u_noise_on != 0) k = reflect_about(k, r);      // the height above the surface stays
    vec3 offset = k.x * t + k.y * b + k.z * n;         // world space
    vec3 q = kernel_point(p, offset, radius);          // in view space
    // [classic-test]
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
    float range = range_weight(radius, -p.z - scene);
    hidden += (scene <= sample_depth - u_bias * radius ? 1.0 : 0.0) * range;
    // [/classic-test]
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
// [/classic]
#endif

#ifdef AO_DISK
// [disk]
float disk_ao(ivec2 pixel, Surface s) {
  float zr = view_depth(s.position);
  // [disk-region]
  // R projected at the receiver's depth, in pixels, clamped near the camera
  float scale_px = u_projection[1][1] * 0.5 * gb_size.y / zr;  // pixels per world unit at depth zr
  float radius_px = min(u_radius * scale_px, u_max_screen_radius * gb_size.y);
  float world_radius = radius_px / scale_px;
  // each sample stands for an equal share of the disk: area pi R^2 / N at the receiver's depth
  float share = PI * world_radius * world_radius / float(u_samples);
  // [/disk-region]
  float occlusion = 0.0;
  // The spiral turned per pixel by the 4x4 noise tile's angle (u_noise_on): the same spiral at
  // every pixel puts its samples on the same offsets everywhere, and where a sample crosses an
  // edge it does so along a whole line of pixels (bands); turned, the tile's 16 spirals
  // interleave and the 4x4 blur averages them.
  vec3 noise = u_noise[(pixel.x & 3) + 4 * (pixel.y & 3)].xyz;
  float turn = u_noise_on != 0 ? atan(noise.y, noise.x) : 0.0;
  for (int i = 0; i < u_samples; ++i) {
    vec2 polar = spiral_polar(i, u_samples, turn);  // radius (of 1), angle
    ivec2 sp = pixel + ivec2(round(polar.x * radius_px * vec2(cos(polar.y), sin(polar.y))));
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
    // [disk-term]
    if (d2 > u_radius * u_radius || d2 <= 0.0) continue;  // beyond the rays' length R
    vec3 ne = decode_normal(texelFetch(gb_normal, sp, 0));
    float ze = view_depth(e);
    // the share at the emitter's depth, spread over the surface the pixel sees at a slant
    vec3 to_eye = normalize(gb_eye.xyz - e);
    float area = share * (ze / zr) * (ze / zr) / max(abs(dot(ne, to_eye)), 0.2);
#ifdef AO_BUNNELL
    occlusion += bunnell_occlusion(s.position, s.normal, e, ne, area);
#else
    occlusion += form_factor_occlusion(s.position, s.normal, e, ne, area);
#endif
    // [/disk-term]
  }
  return 1.0 - clamp(occlusion, 0.0, 1.0);
}
// [/disk]
#endif


#ifdef AO_GTAO
// [gtao]
// Horizon-based AO with cosine weighting (GTAO, Jimenez et al. 2016; the shape of XeGTAO's
// reference code): in each of a few slices through the view vector, march the depth buffer
// both ways to find the highest horizon within R, then integrate the cosine-weighted
// visibility between the two horizons analytically. 16 depth reads a slice (8 steps a side),
// max(1, u_samples / 16) slices: fewer than 16 samples still read one whole slice. The slices'
// angle and the steps' offset are jittered by the 4x4 noise tile (the blur removes the
// pattern). Unlike XeGTAO, whose falloff starts at 0.385 R (it made the Cornell box's error
// 0.14), occluders count fully to 0.95 R and not at all beyond R: the truth's rays end at R
// (u_falloff = 0.05, untuned; the sweep tunes it).
// gtao_horizon (the horizon cosine one occluder point gives) and gtao_arc (a slice's visibility
// from its normal to a horizon) are in ao_math.glsl.
float gtao_ao(ivec2 pixel, Surface s) {
  // [gtao-budget]
  const int steps = 8;
  int slices = max(1, u_samples / (2 * steps));
  // [/gtao-budget]
  vec3 p = (u_view * vec4(s.position, 1.0)).xyz;
  vec3 view_vec = normalize(-p);
  vec3 normal = normalize(mat3(u_view) * s.normal);
  float z = -p.z;
  float scale_px = u_projection[1][1] * 0.5 * gb_size.y / z;  // pixels per world unit at this depth
  float radius_px = min(u_radius * scale_px, u_max_screen_radius * gb_size.y);
  if (radius_px < 1.0) return 1.0;
  // the falloff: full weight to 0.95 R, none at R
  float falloff_range = u_falloff * u_radius, falloff_from = u_radius - falloff_range;
  float falloff_mul = -1.0 / falloff_range, falloff_add = falloff_from / falloff_range + 1.0;
  vec3 noise = u_noise[(pixel.x & 3) + 4 * (pixel.y & 3)].xyz;  // a unit vector: its angle jitters
  float jitter_angle = u_noise_on != 0 ? (atan(noise.y, noise.x) / (2.0 * PI) + 0.5) : 0.5;
  float jitter_step = u_noise_on != 0 ? fract(jitter_angle * 7.0) : 0.5;
  float visibility = 0.0, open = 0.0;
  for (int i = 0; i < slices; ++i) {
    float phi = (float(i) + jitter_angle) / float(slices) * PI;
    vec2 omega = vec2(cos(phi), sin(phi));            // screen direction (OpenGL: y up, as view space)
    vec3 dir = vec3(omega, 0.0);
    vec3 ortho = dir - dot(dir, view_vec) * view_vec;
    vec3 axis = normalize(cross(ortho, view_vec));
    vec3 projected = normal - axis * dot(normal, axis);
    float projected_len = length(projected);
    if (projected_len < 1e-6) continue;
    float sign_n = dot(ortho, projected) >= 0.0 ? 1.0 : -1.0;
    float cos_n = clamp(dot(projected, view_vec) / projected_len, 0.0, 1.0);
    float n = sign_n * acos_clamped(cos_n);
    float low0 = cos(n + 0.5 * PI), low1 = cos(n - 0.5 * PI);
    float horizon0 = low0, horizon1 = low1;
    for (int j = 0; j < steps; ++j) {
      float t = (float(j) + jitter_step) / float(steps);
      t = t * t;                                        // more samples near the pixel
      vec2 offset = max(t * radius_px, float(j + 1)) * omega;
      for (int side = 0; side < 2; ++side) {
        ivec2 sp = ivec2(round(vec2(pixel) + 0.5 + (side == 0 ? offset : -offset) - 0.5));
        if (any(lessThan(sp, ivec2(0))) || any(greaterThanEqual(sp, ivec2(gb_size.xy)))) continue;
        float depth = texelFetch(gb_depth, sp, 0).r;
        if (sky_depth(depth)) continue;
        vec3 q = (u_view * vec4(world_at(sp, depth), 1.0)).xyz;
        float h = gtao_horizon(p, q, normal, view_vec, side == 0 ? low0 : low1, falloff_mul, falloff_add, u_bias * u_radius);
        // [thickness]
        // The depth buffer holds only each surface's front. A thickness T (u_thickness x the
        // radius) says what lies behind it: the sample stands for a slab from q to T farther
        // along its view ray. When q is beyond the reach but the slab is not (the tall box's
        // front is 0.9 m before the back wall, its back 0.25 m), the slab's highest point within
        // full weight is where its ray enters the sphere of radius falloff_from about p (along
        // the ray the elevation seen from p only falls, so that point is the highest).
        vec3 d = normalize(q);                       // the view ray through q, away from the camera
        vec3 m = q - p;
        float r = u_radius - falloff_range, b = dot(m, d), c0 = dot(m, m) - r * r;
        float disc = b * b - c0;
        if (u_thickness > 0.0 && c0 > 0.0 && disc >= 0.0) {
          float t_in = -b - sqrt(disc);
          if (t_in >= 0.0 && t_in <= u_thickness * u_radius)
            h = max(h, gtao_horizon(p, q + t_in * d, normal, view_vec, side == 0 ? low0 : low1, falloff_mul, falloff_add,
                              u_bias * u_radius));
        }
        // [/thickness]
        if (side == 0) horizon0 = max(horizon0, h);
        else horizon1 = max(horizon1, h);
      }
    }
    // [gtao-arc]
    float h0 = -acos_clamped(horizon1), h1 = acos_clamped(horizon0);  // the - side, the + side
    h0 = n + clamp(h0 - n, -0.5 * PI, 0.5 * PI);
    h1 = n + clamp(h1 - n, -0.5 * PI, 0.5 * PI);
    float arc0 = gtao_arc(h0, n, cos_n), arc1 = gtao_arc(h1, n, cos_n);
    visibility += projected_len * (arc0 + arc1);
    // the same slice with nothing above the tangent plane: cos n + n sin n. Its mean over all
    // slice angles is exactly 1, over a few it is not (0.94 on a floor seen at 27 degrees with
    // 2 slices); dividing by it makes an open surface exactly 1 at any slice count.
    open += projected_len * (cos_n + n * sin(n));
    // [/gtao-arc]
  }
  return open > 0.0 ? clamp(visibility / open, 0.0, 1.0) : 1.0;
}
// [/gtao]
#endif

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(q, imageSize(u_out)))) return;
  ivec2 pixel = min(q * u_scale + u_scale / 2, ivec2(gb_size.xy) - 1);
  Surface s = decode_gbuffer(pixel);
  float ao = 1.0;
  if (!s.is_sky) {
#if defined(AO_CLASSIC)
    ao = classic_ao(pixel, s);
#elif defined(AO_GTAO)
    ao = gtao_ao(pixel, s);
#else
    ao = disk_ao(pixel, s);
#endif
  }
  if (u_power != 1.0) ao = pow(ao, u_power);
  imageStore(u_out, q, vec4(ao));
}
