// Chapter 06's visibility hook (chapter 03's FRAME_VISIBILITY, deferred_frame.h): the sun
// looked up in its shadow map by the method the define SHADOW_METHOD names, or, with
// SHADOW_VOLUMES, read from the visibility its shadow volumes left. ShadowStage::shader_hooks()
// passes the method, its slots (SHADOW_UNIT, SHADOW_BLOCK) and which directional light is the
// sun (SHADOW_SUN_INDEX, from shadowed_sun_index()). The C++ twins are in shadow_math.h. Only
// the sun has a map, the spot lights the scene marks to cast (shadow_stage.h [casts-shadows]) a
// perspective one each in a tile of one atlas (spot_atlas.h) and the marked point lights a cube
// map each (cube_math.h); the other lights keep visibility 1.
#include "03_light_volumes/shaders/hooks/frame_pixel.glsl"
#define SHADOW_HARD 0
#define SHADOW_PCF 1
#define SHADOW_PCF_HARDWARE 2
#define SHADOW_VSM 3
#define SHADOW_ESM 4
#define SHADOW_VOLUMES 5
#define SHADOW_PCSS 6
#define SHADOW_MSM 7
#define SHADOW_CSM_FOURIER 8
#if !defined(SHADOW_METHOD) || !defined(SHADOW_UNIT) || !defined(SHADOW_BLOCK) || !defined(SHADOW_SUN_INDEX)
#error the shadow hook needs SHADOW_METHOD, SHADOW_UNIT, SHADOW_BLOCK and SHADOW_SUN_INDEX (ShadowStage::shader_hooks)
#endif

#if SHADOW_METHOD == SHADOW_VOLUMES
// No map: ShadowStage counted the sun's shadow volumes in the stencil before the lights and
// left 1 (lit) or 0 (in a volume) per pixel of the G-buffer, read here at the pixel being lit.
layout(binding = SHADOW_UNIT + 4) uniform sampler2D sh_volume_visibility;
#define sh_depth sh_volume_visibility  // show_visibility.frag's map view shows this instead

// [volumes-glsl]
float directional_visibility(int index, GpuLight light, Surface s) {
  if (index != SHADOW_SUN_INDEX) return 1.0;
  if (dot(s.normal, -light.direction_range.xyz) <= 0.0) return 1.0;  // faces away, as the maps
  return texelFetch(sh_volume_visibility, ivec2(frame_pixel()), 0).r;
}
// [/volumes-glsl]

float local_visibility(int index, GpuLight light, Surface s) { return 1.0; }
#else

#include "06_shadows/shaders/shadow_block.h"
#include "06_shadows/shaders/geometric_normal.glsl"
layout(std140, binding = SHADOW_BLOCK) uniform ShadowBlock { ShadowParameters sh; };
// The stage's units: the sun's map read raw (nearest) and through the comparison sampler,
// VSM's or ESM's filtered map, and the spots' atlas (+3 is the pre-filter's input, +4 the volumes').
// With cascades (SHADOW_CASCADES > 1) the sun's maps are the layers of an array, on the same
// units; SHADOW_DEPTH and SHADOW_COMPARE read the layer of the cascade being looked up.
#ifndef SHADOW_CASCADES
#define SHADOW_CASCADES 1
#endif
#if SHADOW_CASCADES > 1
layout(binding = SHADOW_UNIT + 0) uniform sampler2DArray sh_cascades;
layout(binding = SHADOW_UNIT + 1) uniform sampler2DArrayShadow sh_cascades_compare;
float sh_layer = 0.0;
#define SHADOW_DEPTH(uv) texture(sh_cascades, vec3(uv, sh_layer))
#define SHADOW_COMPARE(uvz) texture(sh_cascades_compare, vec4((uvz).xy, sh_layer, (uvz).z))
#else
layout(binding = SHADOW_UNIT + 0) uniform sampler2D sh_depth;
layout(binding = SHADOW_UNIT + 1) uniform sampler2DShadow sh_depth_compare;
#define SHADOW_DEPTH(uv) texture(sh_depth, uv)
#define SHADOW_COMPARE(uvz) texture(sh_depth_compare, uvz)
#endif
layout(binding = SHADOW_UNIT + 2) uniform sampler2D sh_moments;
layout(binding = SHADOW_UNIT + 5) uniform sampler2D sh_spot_atlas;
layout(binding = SHADOW_UNIT + 6) uniform samplerCubeArray sh_point_maps;
layout(binding = SHADOW_UNIT + 7) uniform sampler2DArray sh_csm;
#include "06_shadows/shaders/csm_math.glsl"
#include "06_shadows/shaders/msm_math.glsl"
#include "06_shadows/shaders/filtered_math.glsl"
#include "06_shadows/shaders/lookup_math.glsl"

// The map a lookup reads: the sun's one map, or the cascade chosen for the pixel (all share the
// light's view, sh.view, and its depth range, sh.depth_range).
struct SunMap {
  mat4 matrix;         // world to the map's clip space
  float texel_metres;  // one texel, metres
  vec2 extent;         // the map's box across the light, metres
};
SunMap sh_map;

// With --exercise 1 the reader's shadow_lookup() (chapters/06_shadows/exercises/) stands in.
#ifdef EXERCISE_SHADOW_LOOKUP
#include EXERCISE_SHADOW_LOOKUP
#else
// [bias-glsl]
// lookup_math.glsl's normal_offset and slope_scaled_bias in the map's texels; the bias in
// window-depth units (the light's projection is orthographic: depth is linear in metres).
vec3 shadow_lookup(Surface s, vec3 to_light) {
  float cos_theta = dot(s.normal, to_light);
  vec3 p = normal_offset(s.position, s.normal, cos_theta, sh.normal_offset, sh_map.texel_metres);
  vec4 clip = sh_map.matrix * vec4(p, 1.0);
  vec3 window = clip.xyz / clip.w * 0.5 + 0.5;
  float bias = slope_scaled_bias(sh.constant_bias, sh.slope_bias, cos_theta, sh_map.texel_metres) / sh.depth_range;
  return vec3(window.xy, window.z - bias);
}
// [/bias-glsl]
#endif

// With --exercise 3 the reader's receiver_plane_gradient() stands in.
#ifdef EXERCISE_RECEIVER_PLANE
#include EXERCISE_RECEIVER_PLANE
#else
// lookup_math.glsl's receiver_plane_gradient for the map being read (sh_map).
vec2 receiver_plane_gradient(Surface s) {
  return receiver_plane_gradient(mat3(sh.view), s.normal, sh_map.extent, sh.depth_range);
}
#endif

// [poisson-glsl]
// The rotated Poisson disk's taps (shadow_math.h [poisson]): the turn, an angle that
// interleaved gradient noise (Jimenez 2014) draws from the pixel's position, and tap i in the
// unit disk.
mat2 poisson_turn() {
  float angle = 6.2831853 * fract(52.9829189 * fract(dot(frame_pixel(), vec2(0.06711056, 0.00583715))));
  return mat2(cos(angle), sin(angle), -sin(angle), cos(angle));
}
vec2 poisson_tap(int i) {
  vec4 pair = sh.poisson[i / 2];
  return (i & 1) == 0 ? pair.xy : pair.zw;
}
// [/poisson-glsl]

// PCSS's filter radius in metres at the last lookup (show_visibility.frag's penumbra picture).
float sh_pcss_radius = 0.0;

// With --exercise 2 the reader's vsm_visibility(moments, depth) stands in for VSM's lines below.
#ifdef EXERCISE_VSM_BOUND
#include EXERCISE_VSM_BOUND
#endif

// The sun's visibility in the map sh_map (and, with cascades, the layer sh_layer).
float sun_map_visibility(Surface s, vec3 to_light) {
  vec3 q = shadow_lookup(s, to_light);
  // Outside the map's box (sideways or beyond its far plane): nothing casts there, lit.
  if (any(lessThan(q.xy, vec2(0.0))) || any(greaterThan(q.xy, vec2(1.0))) || q.z > 1.0) return 1.0;
#if SHADOW_METHOD == SHADOW_HARD
  // [hard-glsl]
  return q.z <= SHADOW_DEPTH(q.xy).r ? 1.0 : 0.0;
  // [/hard-glsl]
#elif SHADOW_METHOD == SHADOW_PCF
  // [pcf-glsl]
  // k x k comparisons on the texel grid around the lookup, averaged.
  int r = int(sh.pcf_radius);
  float texel = 1.0 / sh.map_size, lit = 0.0;
  vec2 g = receiver_plane_gradient(s);
  int taps = int(sh.poisson_taps);
  if (taps > 0) {
    // Or `taps` comparisons on a Poisson disk k texels across, turned per pixel.
    mat2 turn = poisson_turn();
    float scale = (float(r) + 0.5) * texel;
    for (int i = 0; i < taps; ++i) {
      vec2 o = turn * poisson_tap(i) * scale;
      lit += q.z + dot(g, o) <= SHADOW_DEPTH(q.xy + o).r ? 1.0 : 0.0;
    }
    return lit / float(taps);
  }
  for (int y = -r; y <= r; ++y)
    for (int x = -r; x <= r; ++x) {
      vec2 o = vec2(x, y) * texel;
      lit += q.z + dot(g, o) <= SHADOW_DEPTH(q.xy + o).r ? 1.0 : 0.0;
    }
  return lit / float((2 * r + 1) * (2 * r + 1));
  // [/pcf-glsl]
#elif SHADOW_METHOD == SHADOW_PCF_HARDWARE
  // [pcf-hardware-glsl]
  // The comparison sampler: four comparisons weighted bilinearly in one tap, on the same grid.
  int r = int(sh.pcf_radius);
  float texel = 1.0 / sh.map_size, lit = 0.0;
  vec2 g = receiver_plane_gradient(s);
  for (int y = -r; y <= r; ++y)
    for (int x = -r; x <= r; ++x) {
      vec2 o = vec2(x, y) * texel;
      lit += SHADOW_COMPARE(vec3(q.xy + o, q.z + dot(g, o)));
    }
  return lit / float((2 * r + 1) * (2 * r + 1));
  // [/pcf-hardware-glsl]
#elif SHADOW_METHOD == SHADOW_VSM
#ifdef EXERCISE_VSM_BOUND
  return vsm_visibility(texture(sh_moments, q.xy).xy, q.z);
#else
  return vsm_lit_fraction(texture(sh_moments, q.xy).xy, q.z, sh.min_variance, sh.vsm_p_min);
#endif
#elif SHADOW_METHOD == SHADOW_ESM
  return esm_lit_fraction(texture(sh_moments, q.xy).x, sh.esm_c, q.z);
#elif SHADOW_METHOD == SHADOW_PCSS
  // [pcss-glsl]
  // shadow_math.h's pcss(): depths in window units (q.z: the receiver's) times the box's depth
  // range sh.depth_range are metres from the near plane; a radius in metres is sh.extent apart in
  // the map's (u, v). Every tap compares with the receiver's plane there, as PCF's do.
  float tan_size = sh.tan_sun_radius;
  vec2 g = receiver_plane_gradient(s);
  mat2 turn = poisson_turn();
  int taps = int(sh.poisson_taps);
  // A part of the disk a frame (chapter 11): every parts-th tap from `part`, turned further.
  int part = int(sh.pcss_part), parts = int(sh.pcss_parts);
  turn = turn * mat2(cos(sh.pcss_turn), sin(sh.pcss_turn), -sin(sh.pcss_turn), cos(sh.pcss_turn));
  // 1. The blocker search: whatever can hide part of the sun lies within d_r tan(theta).
  vec2 search = max(q.z * sh.depth_range * tan_size, sh_map.texel_metres) / sh_map.extent;
  float blockers = 0.0, sum = 0.0;
  for (int i = part; i < taps; i += parts) {
    vec2 o = turn * poisson_tap(i) * search;
    float z = SHADOW_DEPTH(q.xy + o).r;
    if (z < q.z + dot(g, o)) sum += z, blockers += 1.0;
  }
  if (blockers == 0.0) return 1.0;  // nothing between the receiver and any of the sun
  // 2. The penumbra: the sun's disk on the blockers' mean depth, (d_r - d_b) tan(theta) across
  // (half a texel at least: below it the map cannot tell).
  float radius = max((q.z - sum / blockers) * sh.depth_range * tan_size, 0.5 * sh_map.texel_metres);
  sh_pcss_radius = radius;
  // 3. PCF over that disk.
  float lit = 0.0;
  for (int i = part; i < taps; i += parts) {
    vec2 o = turn * poisson_tap(i) * (radius / sh_map.extent);
    lit += q.z + dot(g, o) <= SHADOW_DEPTH(q.xy + o).r ? 1.0 : 0.0;
  }
  return lit / float(taps / parts);
  // [/pcss-glsl]
#elif SHADOW_METHOD == SHADOW_MSM
  // the moments (back from the optimised 16-bit map) and the Hamburger reconstruction:
  // msm_math.glsl, the twin of shadow_math.h's
  vec4 b = texture(sh_moments, q.xy);
  if (sh.msm_optimized > 0.5) b = msm_unoptimize(b);
  return msm_hamburger(b, q.z, sh.msm_moment_bias);
#elif SHADOW_METHOD == SHADOW_CSM_FOURIER
  // csm_math.glsl's csm_visibility on the filtered layers the series' terms use
  int terms = int(sh.csm_terms);
  vec4 layers[CSM_MAX_TERMS / 2];
  for (int l = 0; l < CSM_MAX_TERMS / 2; ++l) layers[l] = 2 * l < terms ? texture(sh_csm, vec3(q.xy, float(l))) : vec4(0.0);
  return csm_visibility(layers, q.z, terms);
#else
#error SHADOW_METHOD names no method
#endif
}

// The cascade the last lookup read, plus the next one's weight in a blend band (the cascades
// picture); -1 beyond the last cascade.
float sh_cascade_shown = 0.0;

#if SHADOW_CASCADES > 1
float cascade_visibility(int i, Surface s, vec3 to_light) {
  sh_map = SunMap(sh.cascade_matrix[i], sh.cascade_texel[i], vec2(sh.cascade_extent[i]));
  sh_layer = float(i);
  return sun_map_visibility(s, to_light);
}
#endif

#ifdef SHADOW_SUN_VISIBILITY
layout(binding = SHADOW_UNIT + 8) uniform sampler2D sh_sun_visibility;
#endif

float directional_visibility(int index, GpuLight light, Surface s) {
  if (index != SHADOW_SUN_INDEX) return 1.0;
  vec3 to_light = -light.direction_range.xyz;
  if (dot(s.normal, to_light) <= 0.0) return 1.0;  // faces away: the light adds nothing anyway
#ifdef SHADOW_SUN_VISIBILITY
  // [sun-visibility-glsl]
  // The sun's visibility computed before the lights (chapter 11's accumulation), read for the
  // G-buffer's surface at this pixel; a surface in front of it (the glass) looks up the map.
  ivec2 pixel = ivec2(frame_pixel());
  if (distance(s.position, gbuffer_point(pixel)) <= 1e-4 * distance(s.position, gb_eye.xyz))
    return texelFetch(sh_sun_visibility, pixel, 0).r;
  // [/sun-visibility-glsl]
#endif
  // [geometric-surface-glsl]
  // The lookups below bias and tilt by the surface's geometry, not by its normal map's bumps.
  s.normal = geometric_normal(s);
  // [/geometric-surface-glsl]
#if SHADOW_CASCADES > 1
  // [cascade-lookup-glsl]
  // lookup_math.glsl's choose_cascade at the pixel's view depth: its cascade, faded into the
  // next one in the blend band.
  float depth = dot(sh.camera_depth.xyz, s.position) + sh.camera_depth.w;
  CascadeChoice c = choose_cascade(depth, sh.cascade_far, sh.cascade_near, int(sh.cascade_count), sh.cascade_band);
  sh_cascade_shown = float(c.cascade) + c.next_weight;
  if (c.cascade < 0) return 1.0;  // beyond the last cascade: no map covers it
  float v = cascade_visibility(c.cascade, s, to_light);
  if (c.next_weight > 0.0) v = mix(v, cascade_visibility(c.cascade + 1, s, to_light), c.next_weight);
  return v;
  // [/cascade-lookup-glsl]
#else
  sh_map = SunMap(sh.matrix, sh.texel_metres, sh.extent);
  return sun_map_visibility(s, to_light);
#endif
}

// [spot-glsl]
// A marked spot light (found by its position: the light order is chapter 03's) in its tile of
// the atlas. Distances are linear, metres along the spot's axis (clip w); a texel there is
// w(d) = 2 d tan(cone) / N wide (N: the tile's side), and the biases are shadow_math.h's [bias]
// in units of it: the normal offset, the constant and the slope-scaled parts. Hard: one
// comparison; every other map method: PCF on a k x k grid, each tap compared with the
// receiver's plane where the light's ray through that texel meets it (the perspective form of
// the receiver-plane bias: in the light's view space the ray through the map's (u, v) is
// t (x tan, y tan, -1), x and y in [-1, 1], and it meets the plane n . (X - p) = 0 at
// t = n . p / n . ray, its depth t).
float point_visibility(int i, Surface s);
float spot_visibility(int i, Surface s);
float local_visibility(int index, GpuLight light, Surface s) {
  if (light.position_type.w == LIGHT_POINT) {
    // A point light with a cube map (found by its position, as the spot), or none: lit.
    for (int i = 0; i < int(sh.point_count); ++i)
      if (distance(light.position_type.xyz, sh.point_light[i].xyz) <= 1e-4) return point_visibility(i, s);
    return 1.0;
  }
  if (light.position_type.w != LIGHT_SPOT) return 1.0;
  for (int i = 0; i < int(sh.spot_count); ++i)
    if (distance(light.position_type.xyz, sh.spot[i].position.xyz) <= 1e-4) return spot_visibility(i, s);
  return 1.0;
}

float spot_visibility(int i, Surface s) {
  SpotTile t = sh.spot[i];
  if (t.position.w == 0.0) return 1.0;  // no tile this frame: its reach lies off screen
  vec3 to_light = normalize(t.position.xyz - s.position);
  float cos_theta = dot(s.normal, to_light);
  if (cos_theta <= 0.0) return 1.0;  // faces away: the light adds nothing anyway
  s.normal = geometric_normal(s);  // the spot's biases and taps, as the sun's
  cos_theta = dot(s.normal, to_light);
  float d = (t.matrix * vec4(s.position, 1.0)).w;
  float size = t.frustum.w, tan_cone = t.frustum.z;
  float texel = 2.0 * d * tan_cone / size;
  vec3 offset = normal_offset(s.position, s.normal, cos_theta, sh.normal_offset, texel);  // lookup_math.glsl
  vec4 clip = t.matrix * vec4(offset, 1.0);
  if (clip.w <= t.frustum.x) return 1.0;
  vec3 window = clip.xyz / clip.w * 0.5 + 0.5;
  if (any(lessThan(window.xy, vec2(0.0))) || any(greaterThan(window.xy, vec2(1.0))) || window.z > 1.0) return 1.0;
#if SHADOW_METHOD == SHADOW_HARD
  int r = 0;
#else
  int r = int(sh.pcf_radius);
#endif
  float bias = slope_scaled_bias(sh.constant_bias, sh.slope_bias, cos_theta, texel);
  vec3 p_view = (t.view * vec4(offset, 1.0)).xyz;
  vec3 n_view = mat3(t.view) * s.normal;
  float n = t.frustum.x, f = t.frustum.y, lit = 0.0;
  for (int y = -r; y <= r; ++y)
    for (int x = -r; x <= r; ++x) {
      vec2 uv = window.xy + vec2(x, y) / size;
      vec3 ray = vec3((2.0 * uv - 1.0) * tan_cone, -1.0);
      float across = dot(n_view, ray);
      float receiver = (r == 0 || abs(across) < 1e-4 ? clip.w : dot(n_view, p_view) / across) - bias;
      float z = 2.0 * texture(sh_spot_atlas, spot_atlas_uv(t.tile.xyz, size, uv)).r - 1.0;  // lookup_math.glsl
      float stored = 2.0 * n * f / (f + n - z * (f - n));  // the map's depth, linear
      lit += receiver <= stored ? 1.0 : 0.0;
    }
  return lit / float((2 * r + 1) * (2 * r + 1));
}
// [/spot-glsl]

// [point-glsl]
// Point light i in its cube map (cube_math.h): the map holds, per direction from the light, the
// distance to the nearest surface. The receiver, pushed out along its normal, is compared by its
// own distance less the bias, both in texels of w(d) = 2 d / N (the spot's biases with tan = 1).
// PCF's taps step a texel at a time across the face the direction falls on, a' = a + (x u + y v)
// 2 / N with a the direction over its major axis and u, v the face's other two axes: a tap past
// the face's edge is a direction on the next face, which the hardware reads there (no seam). Each
// tap compares with the receiver's plane where the tap's ray meets it, t = n . (p - L) / n . a'.
float point_visibility(int i, Surface s) {
  vec4 light = sh.point_light[i];
  if (light.w == 0.0) return 1.0;  // no map this frame: its reach lies off screen
  vec3 to_light = light.xyz - s.position;
  float d = length(to_light);
  float cos_theta = dot(s.normal, to_light / max(d, 1e-6));
  if (cos_theta <= 0.0) return 1.0;  // faces away: the light adds nothing anyway
  s.normal = geometric_normal(s);  // the cube map's biases and taps, as the sun's
  cos_theta = dot(s.normal, to_light / max(d, 1e-6));
  float texel = cube_texel_world(d, sh.point_map_size);  // lookup_math.glsl, as the two below
  vec3 p = normal_offset(s.position, s.normal, cos_theta, sh.normal_offset, texel);
  vec3 from_light = p - light.xyz;
  float receiver = length(from_light);
  if (receiver >= light.w) return 1.0;  // beyond the far plane: nothing drawn there casts
  float bias = slope_scaled_bias(sh.constant_bias, sh.slope_bias, cos_theta, texel);
#if SHADOW_METHOD == SHADOW_HARD
  return receiver - bias <= texture(sh_point_maps, vec4(from_light, float(i))).r * light.w ? 1.0 : 0.0;
#else
  vec3 m = abs(from_light);
  float major = max(m.x, max(m.y, m.z));
  vec3 a = from_light / major;
  vec3 u = m.x == major ? vec3(0, 1, 0) : vec3(1, 0, 0);
  vec3 v = m.z == major ? vec3(0, 1, 0) : vec3(0, 0, 1);
  float plane = dot(s.normal, from_light);  // n . (p - L), below 0: the receiver faces the light
  int r = int(sh.pcf_radius);
  float lit = 0.0;
  for (int y = -r; y <= r; ++y)
    for (int x = -r; x <= r; ++x) {
      vec3 tap = a + (float(x) * u + float(y) * v) * (2.0 / sh.point_map_size);
      float across = dot(s.normal, tap);
      float t = across < -1e-4 ? plane / across : major;  // along tap: the plane's point, or the centre's
      float distance_there = (r == 0 ? receiver : t * length(tap)) - bias;
      lit += distance_there <= texture(sh_point_maps, vec4(tap, float(i))).r * light.w ? 1.0 : 0.0;
    }
  return lit / float((2 * r + 1) * (2 * r + 1));
#endif
}
// [/point-glsl]
#endif  // SHADOW_METHOD
