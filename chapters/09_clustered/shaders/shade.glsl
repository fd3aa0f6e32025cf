// Pass 3 for one pixel: its cell's lights, each lit as chapter 03's local_light() lights it
// (light_pair.glsl: the same formulas, precomputed per light), in the order the list holds
// them (light order). The compute pass (shade.comp) and the
// full-screen fragment pass (shade.frag) both call shade_pixel(); they differ only in how
// the sum reaches the light buffer.
#include "01_forward/shaders/lighting.glsl"
#include "02_gbuffer/shaders/gbuffer.glsl"
#include FRAME_VISIBILITY
#include "09_clustered/shaders/grid.glsl"
#include "09_clustered/shaders/light_pair.glsl"
#ifdef ZBIN
#include "09_clustered/shaders/zbin.glsl"
#endif
#ifdef COUNT_FRAGMENTS
#include "03_light_volumes/shaders/fragment_counters.glsl"
const uint kCountEvaluated = 0u, kCountLit = 1u, kCountSurface = 2u, kCountShared = 3u, kCountMerged = 4u;
// fragment_counters.glsl's count_fragment() adds 1; a pixel adds its whole count at once.
void count_add(uint counter, uint n) {
  if (n == 0u) return;
  if (atomicAdd(fragment_counters[counter].lo, n) > 0xFFFFFFFFu - n) atomicAdd(fragment_counters[counter].hi, 1u);
}
#endif
#ifndef CLUSTERED
layout(std430, binding = 2) readonly buffer Bounds { uint bounds[]; };
#endif

// [tube-shade]
// Chapter 04's tubes (ClusteredLights::set_tubes): each lit by chapter 04's own neon_light(),
// as its capsule volume's fragment shader does (neon_volume.frag), with the method it was
// given. A pass built without them (the glass's clustered forward) adds nothing for a tube.
#ifdef CLUSTER_TUBES
#include "04_neon/shaders/neon.glsl"
layout(std430, binding = CLUSTER_TUBES) readonly buffer Tubes { NeonGpu cluster_tubes[]; };
void add_tube(Surface s, vec3 to_eye, ClusterLight c, inout vec3 diffuse, inout vec3 specular, inout uint lit) {
  NeonSurface surface = NeonSurface(s.position, s.normal, to_eye, s.exponent);
  NeonResult r = neon_light(surface, cluster_tubes[int(c.radiance_inv_range2.w)], NeonMethod(TUBE_METHOD, TUBE_SAMPLES));
  diffuse += r.diffuse;
  specular += s.specular * r.specular;
  if (any(greaterThan(r.diffuse + r.specular, vec3(0.0)))) ++lit;
}
#else
void add_tube(Surface s, vec3 to_eye, ClusterLight c, inout vec3 diffuse, inout vec3 specular, inout uint lit) {}
#endif
// [/tube-shade]

// Light i of the light order, a point or a spot (record c, and its cone when it is a spot:
// grid.glsl's cone_of), added to the pixel's sums. A tube has no cone.
void add_lamp(Surface s, vec3 to_eye, int i, ClusterLight c, vec4 cone, inout vec3 diffuse, inout vec3 specular,
              inout uint lit) {
  light_pair(c, i >= u_first_spot, cone, i, s, to_eye, diffuse, specular, lit);
}
// Any record: a light or a tube (the staged pass, whose loop meets both; Z-binning and the floor
// refuse tubes and add lamps alone).
void add_record(Surface s, vec3 to_eye, int i, ClusterLight c, vec4 cone, inout vec3 diffuse, inout vec3 specular,
                inout uint lit) {
  if (i >= u_first_tube)
    add_tube(s, to_eye, c, diffuse, specular, lit);
  else
    add_lamp(s, to_eye, i, c, cone, diffuse, specular, lit);
}

uint light_of(uvec2 list, uint k) { return list.x == kEveryLight ? k : light_indices[list.x + k]; }

// The k-th light of a cell's list, added to the pixel's sums. A cell whose list did not fit
// (assign.comp: kEveryLight) is shaded from every light in light order: slower, never wrong.
// Not a tube: shade_surface's loop stops before them (they end a list).
void add_light(Surface s, vec3 to_eye, uvec2 list, uint k, inout vec3 diffuse, inout vec3 specular, inout uint lit) {
  int i = int(light_of(list, k));
  add_lamp(s, to_eye, i, cluster_lights[i], cone_of(i), diffuse, specular, lit);
}

#ifdef ZBIN
#ifdef FLOOR
layout(std430, binding = 8) buffer FloorLists { uint floor_lights[]; };  // the exact lists, per pixel
// The floor's lists hold a light where its cut reaches the surface: exactly the lights
// local_light() does not end at their cut (zbin_staged.comp's FLOOR_LISTS builds them).
bool cut_reaches(vec4 position_radius, Surface s) { return distance(position_radius.xyz, s.position) <= position_radius.w; }
#endif
// The record of light i at sorted position p.
SortedRecord zbin_record(uint p, int i) {
#ifdef SORTED_RECORDS
  return sorted_records[p];  // read beside its index, not after it
#else
  return SortedRecord(cluster_lights[i], cone_of(i));
#endif
}
// The light of the lowest bit left in mask word w (if any), added; its bit cleared.
void zbin_take(Surface s, vec3 to_eye, uint w, inout uint m, inout vec3 diffuse, inout vec3 specular, inout uint lit) {
  if (m == 0u) return;
  uint p = w * 32u + uint(findLSB(m));
  int i = int(light_indices[p]);
  m &= m - 1u;
  SortedRecord r = zbin_record(p, i);
  add_lamp(s, to_eye, i, r.light, r.cone, diffuse, specular, lit);
}

// [zbin-loop]
// Z-binning: the lights of the pixel's depth bin's range whose bit its tile has set, in
// sorted (depth) order. tile_words says which of the tile's words have bits: the range's
// empty words are passed over 32 at a time. Four bits an iteration, for llvmpipe's loop limit
// (see the lists' loop).
void zbin_visit(Surface s, vec3 to_eye, ivec2 pixel, inout vec3 diffuse, inout vec3 specular, inout uint evaluated,
                inout uint lit) {
  uvec2 range = zbin_range(zbin_of(view_depth(s.position)));
  uint tile = uint(cell_index(tile_of(pixel), 0)), base = tile * zbin_words();
  uint w0 = range.x >> 5u, w1 = range.y >> 5u;
  if (range.x <= range.y)
    for (uint k = w0 >> 5u; k <= w1 >> 5u; ++k) {
      uint words = cut_to_span(tile_words[tile * zbin_word_words() + k], k, w0, w1);
      while (words != 0u) {
        uint w = k * 32u + uint(findLSB(words));
        words &= words - 1u;
        uint m = cut_to_span(tile_masks[base + w], w, range.x, range.y);
        evaluated += uint(bitCount(m));
        while (m != 0u) {
          zbin_take(s, to_eye, w, m, diffuse, specular, lit);
          zbin_take(s, to_eye, w, m, diffuse, specular, lit);
          zbin_take(s, to_eye, w, m, diffuse, specular, lit);
          zbin_take(s, to_eye, w, m, diffuse, specular, lit);
        }
      }
    }
}
// [/zbin-loop]
#endif

// With counting on, one surface pixel's counts (shade_staged.comp calls it too).
void count_pixel(uint evaluated, uint lit) {
#ifdef COUNT_FRAGMENTS
  count_add(kCountEvaluated, evaluated);
  count_add(kCountLit, lit);
  count_add(kCountSurface, 1u);
#endif
}

// The subgroup operations the shading uses where the driver has them (ClusteredLights picks
// one at compile time, shade.comp enables its extensions): the first active invocation's
// value, and whether a condition holds in every active invocation.
#if defined(SUBGROUP_KHR)
uint subgroup_first(uint v) { return subgroupBroadcastFirst(v); }
bool subgroup_all(bool b) { return subgroupAll(b); }
#elif defined(SUBGROUP_ARB)
uint subgroup_first(uint v) { return readFirstInvocationARB(v); }
bool subgroup_all(bool b) { return allInvocationsARB(b); }
#endif
#ifdef SUBGROUP_LISTS
// The k-th light of a list every active invocation shares: its index made subgroup-uniform, so
// that the index and the light's record are read once for the subgroup (a scalar load), not
// once per invocation. Each invocation adds the same lights in the same order as add_light.
void add_shared_light(Surface s, vec3 to_eye, uvec2 list, uint k, inout vec3 diffuse, inout vec3 specular,
                      inout uint lit) {
  int i = int(subgroup_first(light_of(list, k)));
  add_lamp(s, to_eye, i, cluster_lights[i], cone_of(i), diffuse, specular, lit);
}
#ifdef SUBGROUP_MERGE
// One round of the walk over lists that differ (below): the invocations still walking agree on
// the light the first of them is at; those at it add it and step on (the first always does).
void merge_round(Surface s, vec3 to_eye, uvec2 list, inout uint at, inout vec3 diffuse, inout vec3 specular,
                 inout uint lit) {
  if (at >= list.y) return;
  uint mine = light_of(list, at);
  uint taken = subgroup_first(mine);
  if (mine != taken) return;
  int i = int(taken);
  add_lamp(s, to_eye, i, cluster_lights[i], cone_of(i), diffuse, specular, lit);
  ++at;
}
#endif
#endif

// [shade-pixel]
// diffuse goes to L1, specular (already tinted by the surface's specular colour) to L2;
// `evaluated` lights were looked at, `lit` of them added anything. `pixel` names the cell's
// tile, the surface's view depth its slice: the G-buffer's pixel here, a forward fragment's
// gl_FragCoord in clustered_forward.glsl.
void shade_surface(Surface s, ivec2 pixel, out vec3 diffuse, out vec3 specular, out uint evaluated, out uint lit) {
  diffuse = specular = vec3(0.0);
  evaluated = lit = 0u;
  if (s.is_sky) return;
  vec3 to_eye = normalize(gb_eye.xyz - s.position);  // the pixel's, for each of its lights
#ifdef FLOOR
  // The floor: the pixel's exact list (zbin_staged.comp's FLOOR_LISTS), no culling left to do; a pixel
  // whose list did not fit falls back to the Z-binning below.
  uvec2 exact = cells[pixel.y * u_grid.x + pixel.x];
  if (exact.x != kEveryLight) {
    for (uint k = 0u; k < exact.y; ++k) {
      int i = int(floor_lights[exact.x + k]);
      add_lamp(s, to_eye, i, cluster_lights[i], cone_of(i), diffuse, specular, lit);
    }
    evaluated = exact.y;
    count_pixel(evaluated, lit);
    return;
  }
#endif
#ifdef ZBIN
  zbin_visit(s, to_eye, pixel, diffuse, specular, evaluated, lit);
  count_pixel(evaluated, lit);
  return;
#endif
#ifdef CLUSTERED
  uvec2 list = cells[cell_index(tile_of(pixel), slice_of(view_depth(s.position)))];
#else
  uvec2 list = cells[cell_index(tile_of(pixel), 0)];
#endif
  // [tube-split]
  // Chapter 04's tubes end a list (light order): the lights' loop below stops before them, so
  // that its unrolled body never holds neon_light(); they follow, one at a time.
  uint listed = list.y;
  while (list.y > 0u && int(light_of(list, list.y - 1u)) >= u_first_tube) --list.y;
  // [/tube-split]
#ifdef SUBGROUP_LISTS
  // [subgroup-loop]
  // Where every active invocation of the subgroup shades from one list (a tile's, a cluster's),
  // the loop runs on the first one's list: the same lights in the same order, read once.
  uvec2 first = uvec2(subgroup_first(list.x), subgroup_first(list.y));
  uint first_listed = subgroup_first(listed);
  if (subgroup_all(list == first && listed == first_listed)) {
    for (uint k = 0u; k < first.y; k += 4u) {
      add_shared_light(s, to_eye, first, k, diffuse, specular, lit);
      if (k + 1u < first.y) add_shared_light(s, to_eye, first, k + 1u, diffuse, specular, lit);
      if (k + 2u < first.y) add_shared_light(s, to_eye, first, k + 2u, diffuse, specular, lit);
      if (k + 3u < first.y) add_shared_light(s, to_eye, first, k + 3u, diffuse, specular, lit);
    }
    for (uint k = first.y; k < first_listed; ++k)
      add_tube(s, to_eye, cluster_lights[subgroup_first(light_of(first, k))], diffuse, specular, lit);
    evaluated = first_listed;
    count_pixel(evaluated, lit);
#ifdef COUNT_FRAGMENTS
    count_add(kCountShared, 1u);
#endif
    return;
  }
  // [/subgroup-loop]
#ifdef SUBGROUP_MERGE
  // [subgroup-merge]
  // Lists that differ within the subgroup, walked together (scalarised): each round takes the
  // light that the first invocation still walking is at; the invocations whose list holds it
  // add it (its index and record one value for them all) and step on. Each invocation still
  // adds its own lights in its list's order, so its sums are the loop's below, bit for bit.
  // Four rounds an iteration, for llvmpipe's loop limit.
  uint at = 0u;
  while (at < list.y) {
    merge_round(s, to_eye, list, at, diffuse, specular, lit);
    merge_round(s, to_eye, list, at, diffuse, specular, lit);
    merge_round(s, to_eye, list, at, diffuse, specular, lit);
    merge_round(s, to_eye, list, at, diffuse, specular, lit);
  }
  for (; at < listed; ++at) add_tube(s, to_eye, cluster_lights[light_of(list, at)], diffuse, specular, lit);  // then the tubes
  evaluated = listed;
  count_pixel(evaluated, lit);
#ifdef COUNT_FRAGMENTS
  count_add(kCountMerged, 1u);
#endif
  return;
  // [/subgroup-merge]
#endif
#endif
  // [shade-loop]
  // Four lights an iteration: llvmpipe ends a shader's loops after 65 535 iterations in all
  // (gallivm's loop limiter), and a tile's list can hold 100 000 lights (262 140 at most here).
  for (uint k = 0u; k < list.y; k += 4u) {
    add_light(s, to_eye, list, k, diffuse, specular, lit);
    if (k + 1u < list.y) add_light(s, to_eye, list, k + 1u, diffuse, specular, lit);
    if (k + 2u < list.y) add_light(s, to_eye, list, k + 2u, diffuse, specular, lit);
    if (k + 3u < list.y) add_light(s, to_eye, list, k + 3u, diffuse, specular, lit);
  }
  for (uint k = list.y; k < listed; ++k) add_tube(s, to_eye, cluster_lights[light_of(list, k)], diffuse, specular, lit);
  evaluated = listed;
  // [/shade-loop]
  count_pixel(evaluated, lit);
}

void shade_pixel(ivec2 pixel, out vec3 diffuse, out vec3 specular, out uint evaluated, out uint lit) {
  shade_surface(decode_gbuffer(pixel), pixel, diffuse, specular, evaluated, lit);
}
// [/shade-pixel]

// What the pass adds into L1 and L2: the light, or a heat map's count (chapter 03's
// Output::HeatShaded / HeatLit: lights evaluated, or lights that lit the pixel).
void output_of(vec3 diffuse, vec3 specular, uint evaluated, uint lit, out vec4 l1, out vec4 l2) {
#if defined(HEAT_SHADED)
  l1 = vec4(float(evaluated));
  l2 = vec4(0.0);
#elif defined(HEAT_LIT)
  l1 = vec4(float(lit));
  l2 = vec4(0.0);
#else
  l1 = vec4(diffuse, 0.0);
  l2 = vec4(specular, 0.0);
#endif
}

void pixel_output(ivec2 pixel, out vec4 l1, out vec4 l2) {
  vec3 diffuse, specular;
  uint evaluated, lit;
  shade_pixel(pixel, diffuse, specular, evaluated, lit);
  output_of(diffuse, specular, evaluated, lit, l1, l2);
}
