#version 450
// Chapter 08's one pass of screen-space AO and one-bounce diffuse interreflection, one
// invocation per pixel. Each sample i of the pattern (gi_math.h's pattern_point) is read
// twice: in the narrow disk (radius R_ao, chapter 07's 2D-disk AO with the form factor) and in
// the wide one (R_gi, 5 R_ao by default: the source's 1:5), where the G-buffer gives the
// emitter's position and normal and the light buffer its diffuse light, and the disk transfer
// (gi_math.h's disk_transfer, its C++ twin) carries albedo x L1 to the pixel. Writes rgb: the
// indirect diffuse light L1_ind (before the receiver's albedo, in the light buffer's units),
// a: the visibility A of the narrow disk. The sky gets (0, 0, 0, 1): no light to it.
layout(local_size_x = 8, local_size_y = 8) in;
#include "02_gbuffer/shaders/gbuffer.glsl"

layout(rgba16f, binding = 0) uniform writeonly image2D u_out;
layout(r32f, binding = 1) uniform writeonly image2D u_transfer_out;  // u_keep_transfer: the clamp's denominator
uniform int u_keep_transfer;                                         // (chapter 11 accumulates it)
layout(binding = 9) uniform sampler2D u_light;   // chapter 03's L1: direct diffuse light
layout(binding = 10) uniform sampler2D u_extra;  // a first bounce's L1_ind (u_bounce = 1), else unused

uniform mat4 u_view, u_projection;
uniform int u_samples;               // samples of the pattern actually used (regular: rings x spokes)
uniform int u_rings, u_spokes;       // the regular pattern
uniform int u_pattern;               // 0 regular, 1 spiral, 2 randomised
uniform float u_ao_radius, u_gi_radius;    // world units
uniform float u_max_screen_radius;         // the wide disk: at most this fraction of the image height
uniform int u_bounce;                       // 1: the emitters' light includes u_extra (a second pass)
uniform int u_indirect_on, u_ao_on;
uniform int u_gather;                       // 0 the source's disk (no visibility), 1 slices with a visibility bitmask
uniform float u_thickness;                  // bitmask: the depth each sample is taken to have, world units
uniform int u_back_faces;                   // 1: the disk gather also reads the back-face layer (back_faces.h)
uniform int u_parts, u_part;                // this frame's part of a pattern of u_samples x u_parts points
uniform float u_turn;                       // radians added to the randomised pattern's turn
layout(binding = 11) uniform sampler2D u_back_depth;   // the nearest back face: window depth (sky: none)
layout(binding = 12) uniform sampler2D u_back_normal;  // its own normal (facing away from the camera), encoded
layout(binding = 13) uniform sampler2D u_back_albedo;
layout(binding = 14) uniform sampler2D u_back_light;   // its direct diffuse light L1

bool sky_depth(float depth) { return depth == gb_depth_info.z; }
vec3 world_at(ivec2 pixel, float depth) { return reconstruct_position(vec2(pixel) + 0.5, depth); }
float view_depth(vec3 world) { return -(u_view * vec4(world, 1.0)).z; }

// The pattern, the pixel's jitter and the disk transfer: gi_math.glsl, with their C++ twins'
// test (tests/unit/test_08_twins_gl.cpp). Exercises 1-3 (chapters/08_ssgi/exercises/) stand
// in for the functions so marked (the transfer's in gi_math.glsl).
#include "08_ssgi/shaders/gi_math.glsl"
#ifdef EXERCISE_PATTERN_POINT
#include EXERCISE_PATTERN_POINT
#else
vec2 pattern_point(int i, vec2 jitter) { return pattern_point(u_pattern, i, u_samples * u_parts, u_rings, u_spokes, jitter); }
#endif

// The area a sample stands for: its share of the disk at the receiver's depth zr, grown to the
// emitter's depth ze and spread over the surface the pixel sees at a slant (chapter 07's disk).
#ifdef EXERCISE_SAMPLE_AREA
#include EXERCISE_SAMPLE_AREA
#else
float sample_area(float share, float zr, vec3 e, vec3 ne) {
  float ze = view_depth(e);
  return share * (ze / zr) * (ze / zr) / max(abs(dot(ne, normalize(gb_eye.xyz - e))), 0.2);
}
#endif

// [back-faces-glsl]
// The back-face layer's emitter at the sample's pixel sp: the nearest surface there that faces
// away from the camera (behind what the front layer shows, or where nothing faces the camera),
// sending its albedo x L1 through the same disk transfer, its sample standing for the same
// share of the disk. It needs no test against the front layer: the transfer's cosines already
// keep a back face from lighting a receiver it faces away from.
void back_face_emitter(ivec2 sp, Surface s, float zr, float share, inout vec3 indirect, inout float transfer) {
  float depth = texelFetch(u_back_depth, sp, 0).r;
  if (sky_depth(depth)) return;  // no back face at this pixel
  vec3 e = world_at(sp, depth);
  vec3 v = e - s.position;
  float d2 = dot(v, v);
  if (d2 > u_gi_radius * u_gi_radius || d2 <= 0.0) return;
  vec3 ne = decode_normal(texelFetch(u_back_normal, sp, 0));
  float f = disk_transfer(s.position, s.normal, e, ne, sample_area(share, zr, e, ne));
  indirect += texelFetch(u_back_albedo, sp, 0).rgb * texelFetch(u_back_light, sp, 0).rgb * f;
  transfer += f;
}
// [/back-faces-glsl]

// [bitmask-glsl]
// Beyond the source: the wide disk's light gathered along slices with a visibility bitmask
// (Therrien et al. 2023). The same samples' budget (u_samples, 2 x 8 steps a slice, at least one
// slice) is spent on slices through the view vector, each marched both ways from the pixel,
// nearest first, at radii that keep each sample's share of the disk equal (sqrt spacing: the
// same gi_share as the disk's samples, so the same disk_transfer carries the same light). The
// slice's hemisphere about the normal is cut into 32 sectors of equal angle; a sample, taken as
// a slab u_thickness deep behind its depth, covers the sectors between its front and back
// angles; its light counts only if the sector of its front is not covered by a nearer sample of
// its slice: light behind the short box stops at the box. (Weighting by the uncovered share of
// its own slab instead let each sample of one wall hide the next: 0.70 of the true energy
// captured, against 0.76 this way.)
vec3 bitmask_indirect(ivec2 pixel, Surface s, float gi_px, float gi_share, vec2 jitter, out float transfer) {
  const int steps = 8;
  int slices = max(1, u_samples / (2 * steps));
  float share = gi_share * float(u_samples) / float(2 * steps * slices);
  vec3 p = (u_view * vec4(s.position, 1.0)).xyz;
  vec3 view_vec = normalize(-p);
  vec3 normal = normalize(mat3(u_view) * s.normal);
  float zr = -p.z;
  vec3 indirect = vec3(0.0);
  transfer = 0.0;
  for (int i = 0; i < slices; ++i) {
    float phi = (float(i) + jitter.x) / float(slices) * PI;
    vec2 omega = vec2(cos(phi), sin(phi));
    vec3 dir = vec3(omega, 0.0);
    vec3 ortho = normalize(dir - dot(dir, view_vec) * view_vec);   // the slice's direction, seen square
    vec3 axis = normalize(cross(ortho, view_vec));
    vec3 projected = normal - axis * dot(normal, axis);
    float projected_len = length(projected);
    if (projected_len < 1e-6) continue;
    float sign_n = dot(ortho, projected) >= 0.0 ? 1.0 : -1.0;
    float n = sign_n * acos(clamp(dot(projected, view_vec) / projected_len, -1.0, 1.0));
    uint occluded = 0u;
    for (int j = 0; j < steps; ++j) {
      float r = sqrt((float(j) + jitter.y) / float(steps)) * gi_px;
      for (int side = 0; side < 2; ++side) {
        float sgn = side == 0 ? 1.0 : -1.0;
        ivec2 sp = pixel + ivec2(round(sgn * r * omega));
        if (sp == pixel || any(lessThan(sp, ivec2(0))) || any(greaterThanEqual(sp, ivec2(gb_size.xy)))) continue;
        float depth = texelFetch(gb_depth, sp, 0).r;
        if (sky_depth(depth)) continue;  // the sky sends nothing and hides nothing
        vec3 e = world_at(sp, depth);
        vec3 q = (u_view * vec4(e, 1.0)).xyz;
        vec3 front = q - p, back = q + normalize(q) * u_thickness - p;
        // the angles in the slice from the view vector, + toward omega, then as fractions of
        // the hemisphere about the normal's angle n: 0 and 1 are its two horizons
        float a0 = sgn * acos(clamp(dot(normalize(front), view_vec), -1.0, 1.0));
        float a1 = sgn * acos(clamp(dot(normalize(back), view_vec), -1.0, 1.0));
        vec2 h = clamp((vec2(min(a0, a1), max(a0, a1)) - n) / PI + 0.5, 0.0, 1.0);
        uint lo = uint(floor(h.x * 32.0)), hi = uint(ceil(h.y * 32.0));
        uint span = hi - lo;
        uint mask = span >= 32u ? 0xffffffffu : span == 0u ? 0u : ((1u << span) - 1u) << lo;
        vec3 v = e - s.position;
        float d2 = dot(v, v);
        if (d2 > u_gi_radius * u_gi_radius || d2 <= 0.0) continue;  // beyond R: neither sends nor hides
        float hf = clamp((a0 - n) / PI + 0.5, 0.0, 0.99999);
        float seen = (occluded & (1u << uint(hf * 32.0))) == 0u ? 1.0 : 0.0;
        occluded |= mask;
        if (seen <= 0.0) continue;
        vec3 ne = decode_normal(texelFetch(gb_normal, sp, 0));
        vec3 light = texelFetch(u_light, sp, 0).rgb;
        if (u_bounce == 1) light += texelFetch(u_extra, sp, 0).rgb;
        vec3 albedo = texelFetch(gb_albedo, sp, 0).rgb;
        float f = seen * disk_transfer(s.position, s.normal, e, ne, sample_area(share, zr, e, ne));
        indirect += albedo * light * f;
        transfer += f;
      }
    }
  }
  return indirect;
}
// [/bitmask-glsl]

// [ssgi]
void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, ivec2(gb_size.xy)))) return;
  Surface s = decode_gbuffer(pixel);
  if (s.is_sky) {
    imageStore(u_out, pixel, vec4(0.0, 0.0, 0.0, 1.0));
    if (u_keep_transfer != 0) imageStore(u_transfer_out, pixel, vec4(0.0));
    return;
  }
  float zr = view_depth(s.position);
  // [ssgi-radii]
  float scale_px = u_projection[1][1] * 0.5 * gb_size.y / zr;  // pixels per world unit at depth zr
  // the wide disk clamped on the screen near the camera, the narrow one kept at its ratio
  float gi_px = min(u_gi_radius * scale_px, u_max_screen_radius * gb_size.y);
  float ao_px = gi_px * (u_ao_radius / u_gi_radius);
  float gi_world = gi_px / scale_px, ao_world = ao_px / scale_px;
  // each sample's share of the disk: of the whole pattern's points (u_parts x u_samples)
  float gi_share = PI * gi_world * gi_world / float(u_samples * u_parts);
  float ao_share = PI * ao_world * ao_world / float(u_samples * u_parts);
  // [/ssgi-radii]
  vec2 jitter = vec2(0.5);
  if (u_pattern == 2) {
    jitter = pixel_jitter(pixel);
    jitter.x = fract(jitter.x + u_turn / (2.0 * PI));  // chapter 11: this frame's turn
  }
  vec3 indirect = vec3(0.0);
  float occlusion = 0.0, transfer = 0.0;
  for (int i = 0; i < u_samples; ++i) {
    vec2 u = pattern_point(i * u_parts + u_part, jitter);  // this frame's part (all of it: u_parts 1)
    for (int wide = 0; wide < 2; ++wide) {
      if ((wide == 0 && u_ao_on == 0) || (wide == 1 && (u_indirect_on == 0 || u_gather != 0))) continue;
      float radius = wide == 1 ? u_gi_radius : u_ao_radius;
      ivec2 sp = pixel + ivec2(round(u * (wide == 1 ? gi_px : ao_px)));
      if (sp == pixel || any(lessThan(sp, ivec2(0))) || any(greaterThanEqual(sp, ivec2(gb_size.xy)))) continue;
      if (wide == 1 && u_back_faces != 0) back_face_emitter(sp, s, zr, gi_share, indirect, transfer);
      float depth = texelFetch(gb_depth, sp, 0).r;
      if (sky_depth(depth)) continue;  // the sky sends nothing and hides nothing
      vec3 e = world_at(sp, depth);
      vec3 v = e - s.position;
      float d2 = dot(v, v);
      if (d2 > radius * radius || d2 <= 0.0) continue;
      vec3 ne = decode_normal(texelFetch(gb_normal, sp, 0));
      float area = sample_area(wide == 1 ? gi_share : ao_share, zr, e, ne);
      if (wide == 0) {
        // chapter 07's disk AO with the form factor: a surface blocks from either side
        v *= inversesqrt(d2);
        occlusion += area * abs(dot(ne, v)) * max(dot(s.normal, v), 0.0) / (PI * d2 + area);
      } else {
        // [ssgi-emitter]
        vec3 light = texelFetch(u_light, sp, 0).rgb;
        if (u_bounce == 1) light += texelFetch(u_extra, sp, 0).rgb;
        vec3 albedo = texelFetch(gb_albedo, sp, 0).rgb;  // what the emitter reflects of it
        float f = disk_transfer(s.position, s.normal, e, ne, area);
        indirect += albedo * light * f;
        transfer += f;
        // [/ssgi-emitter]
      }
    }
  }
  if (u_gather == 1 && u_indirect_on != 0) indirect = bitmask_indirect(pixel, s, gi_px, gi_share, jitter, transfer);
  // A part of the pattern stands for all of it: its sums times the parts, so the mean of the
  // parts' results is the whole pattern's (where the clamps below do not act).
  occlusion *= float(u_parts);
  indirect *= float(u_parts);
  transfer *= float(u_parts);
  // [ssgi-clamp]
  // The form factors from a point to surfaces that do not overlap sum to at most 1 (the whole
  // hemisphere). Large sample disks close to the pixel (a wall beside the floor) overlap and
  // can sum to more: scale them back to 1, as the AO's occlusion is clamped.
  if (transfer > 1.0) indirect /= transfer;
  // [/ssgi-clamp]
  imageStore(u_out, pixel, vec4(indirect, 1.0 - clamp(occlusion, 0.0, 1.0)));
  if (u_keep_transfer != 0) imageStore(u_transfer_out, pixel, vec4(transfer, 0.0, 0.0, 0.0));
}
// [/ssgi]
