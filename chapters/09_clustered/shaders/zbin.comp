#version 450
// Z-binning's assignment (zbin.glsl), seven dispatches of this file, one STEP each:
//   0 CLEAR:   the last frame's set words of the tiles' masks zeroed, found from tile_words;
//   1 KEYS:    each light's key, its centre's view depth in 16 384 exponential buckets, counted;
//   2 SCAN:    one work group turns the counts into each bucket's first sorted position;
//   3 SCATTER: each light takes a place in its bucket: light_indices is the sorted order;
//   4 BINS:    each sorted light widens the range of every depth bin its extent reaches
//              (a work group's lights together, in shared memory, then once a bin);
//   5 TILES:   each sorted light sets its bit in the tiles its screen rectangle covers
//              whose boxes (the tile's own depth bounds) its sphere reaches; a light whose
//              rectangle is large (near the eye) is passed on to
//   6 WIDE:    a work group a light, its invocations sharing the rectangle's tiles.
// Every step costs what its lights cover (bins, tiles), never lights x tiles. The order
// inside a bucket is the atomics' (it may differ from frame to frame): the lights a pixel
// adds are the same, their float sum may differ by rounding.
#include "09_clustered/shaders/grid.glsl"
#include "09_clustered/shaders/zbin.glsl"

layout(local_size_x = 256) in;
const uint kSortKeys = 16384u;
#if STEP < 5
layout(std430, binding = 8) buffer ZSort {
  uint sort_hist[kSortKeys];  // per bucket: lights, then (SCAN) its next free sorted position
  uint sort_key[];            // per light
};
#else
// The sort's scratch, free once the lights are sorted: the lights whose screen rectangles
// cover more than kOwnTiles tiles (their sorted positions), which step 6 takes a group each.
const int kOwnTiles = 16;
layout(std430, binding = 8) buffer ZWide {
  uint wide_count;  // (zeroed before step 5)
  uint wide_unused[kSortKeys - 1u];
  uint wide_lights[];
};
#endif
layout(std430, binding = 2) readonly buffer Bounds { uint bounds[]; };
layout(std430, binding = 5) buffer ListState {
  uint head, capacity, cells_over, over_lo, over_hi, needed_lo, needed_hi, max_count;
} state;

uint lights() { return uint(u_tiles.w); }

#if STEP == 2
shared uint s_sum[256];
#elif STEP == 4
const uint kGroupBins = 1024u;  // 8 KiB of shared memory: the default bins (ClusterSettings::zbins) fit
shared uint s_span[2], s_lo[kGroupBins], s_hi[kGroupBins];
#endif

#if STEP == 4
// Sorted light g's depth bins, first and last (empty, first > last, when no surface is that
// near or far, or past the last light).
ivec2 bins_reached(uint g) {
  if (g >= lights()) return ivec2(0, -1);
  vec4 l = cluster_lights[light_indices[g]].position_radius;
  vec2 e = zbin_extent(view_depth(l.xyz), l.w);
  if (e.y < u_depth_range.x || e.x > u_depth_range.y) return ivec2(0, -1);
  return ivec2(zbin_of(e.x), zbin_of(e.y));
}
#endif

#if STEP >= 5
// [zbin-tile]
// Sorted light g's bit in one tile, set when its sphere (view-space centre c, radius r) meets
// the tile's box (the tile's own depth bounds, as tiled tests); a word's first bit also marks
// the word in tile_words. entries counts the bits set.
void zbin_tile(uint g, vec3 c, float r, ivec2 tile, inout uint entries) {
  int ti = tile.y * u_tiles.x + tile.x;
  if (bounds[2 * ti] > bounds[2 * ti + 1]) return;  // no surface in the tile
  ivec2 p0 = tile * u_grid.zw, p1 = min(p0 + u_grid.zw, u_grid.xy);
  Box box = cell_box(p0, p1, uintBitsToFloat(bounds[2 * ti]), uintBitsToFloat(bounds[2 * ti + 1]));
  if (!sphere_meets_box(c, r, box)) return;
  uint word = g / 32u, bit = 1u << (g % 32u);
  if (atomicOr(tile_masks[uint(ti) * zbin_words() + word], bit) == 0u)  // the word's first bit
    atomicOr(tile_words[uint(ti) * zbin_word_words() + word / 32u], 1u << (word % 32u));
  ++entries;
}
// [/zbin-tile]

// Sorted light g's view-space centre and radius, and its screen rectangle (zbin.glsl's
// sphere_tiles) as its first tile and size in tiles (0 x 0 when empty).
struct LightRect {
  vec3 c;
  float r;
  ivec2 first, size;
};
LightRect light_rect(uint g) {
  vec4 l = cluster_lights[light_indices[g]].position_radius;
  vec3 c = (u_view * vec4(l.xyz, 1.0)).xyz;
  ivec4 rect = sphere_tiles(c, l.w);  // empty when nearer than the near plane
  return LightRect(c, l.w, rect.xy, max(rect.zw - rect.xy + 1, ivec2(0)));
}

// The list entries, as the other modes count theirs: (tile, light) pairs. (The floor counts
// its own lists' entries.)
void count_entries(uint entries) {
#ifndef FLOOR
  if (entries > 0u && atomicAdd(state.needed_lo, entries) > 0xFFFFFFFFu - entries) atomicAdd(state.needed_hi, 1u);
#endif
}
#endif

void main() {
  uint g = gl_GlobalInvocationID.x;
#if STEP == 0
  // [zbin-clear]
  // One invocation a word of tile_words (as many invocations as the dispatch has, striding):
  // each bit set names a mask word the last frame wrote; only those are zeroed.
  uint per_tile = zbin_word_words(), total = uint(u_tiles.x * u_tiles.y) * per_tile;
  for (uint i = g; i < total; i += gl_NumWorkGroups.x * gl_WorkGroupSize.x) {
    uint set = tile_words[i];
    if (set == 0u) continue;
    uint first = (i / per_tile) * zbin_words() + (i % per_tile) * 32u;
    while (set != 0u) {
      tile_masks[first + uint(findLSB(set))] = 0u;
      set &= set - 1u;
    }
    tile_words[i] = 0u;
  }
  // [/zbin-clear]
#elif STEP == 1
  // [zbin-keys]
  if (g >= lights()) return;
  float d = view_depth(cluster_lights[g].position_radius.xyz);
  float t = log(max(d, u_depth_range.x) / u_depth_range.x) / log(u_depth_range.y / u_depth_range.x);
  uint key = uint(clamp(floor(t * float(kSortKeys)), 0.0, float(kSortKeys - 1u)));
  sort_key[g] = key;
  atomicAdd(sort_hist[key], 1u);
  // [/zbin-keys]
#elif STEP == 2
  // 64 buckets an invocation: its own sum, then the 256 sums' exclusive prefix.
  const uint per = kSortKeys / 256u;
  uint t = gl_LocalInvocationIndex, sum = 0u;
  for (uint k = 0u; k < per; ++k) sum += sort_hist[t * per + k];
  s_sum[t] = sum;
  barrier();
  if (t == 0u) {
    uint total = 0u;
    for (uint k = 0u; k < 256u; ++k) {
      uint c = s_sum[k];
      s_sum[k] = total;
      total += c;
    }
  }
  barrier();
  uint at = s_sum[t];
  for (uint k = 0u; k < per; ++k) {
    uint c = sort_hist[t * per + k];
    sort_hist[t * per + k] = at;
    at += c;
  }
#elif STEP == 3
  if (g >= lights()) return;
  // [zbin-scatter]
  uint p = atomicAdd(sort_hist[sort_key[g]], 1u);
  light_indices[p] = g;
#ifdef SORTED_RECORDS
  sorted_records[p] = SortedRecord(cluster_lights[g], cone_of(int(g)));
#endif
  // [/zbin-scatter]
#elif STEP == 4
  // The group's lights are neighbours in depth (nearly the same bins): their minima and maxima
  // are taken in shared memory, then written once a bin. A group whose bins are more than
  // kGroupBins apart writes from each light.
  // [zbin-bins]
  uint t = gl_LocalInvocationIndex;
  ivec2 reach = bins_reached(g);
  if (t == 0u) { s_span[0] = 0xFFFFFFFFu; s_span[1] = 0u; }
  barrier();
  if (reach.x <= reach.y) {
    atomicMin(s_span[0], uint(reach.x));
    atomicMax(s_span[1], uint(reach.y));
  }
  barrier();
  uint first = s_span[0], count = s_span[0] <= s_span[1] ? s_span[1] - s_span[0] + 1u : 0u;
  if (count > kGroupBins) {  // the same for the whole group: it reads one shared value
    for (int b = reach.x; b <= reach.y; ++b) {
      atomicMin(zbins[2 * b], g);
      atomicMax(zbins[2 * b + 1], g);
    }
    return;
  }
  for (uint i = t; i < count; i += gl_WorkGroupSize.x) { s_lo[i] = 0xFFFFFFFFu; s_hi[i] = 0u; }
  barrier();
  for (int b = reach.x; b <= reach.y; ++b) {
    atomicMin(s_lo[uint(b) - first], g);
    atomicMax(s_hi[uint(b) - first], g);
  }
  barrier();
  for (uint i = t; i < count; i += gl_WorkGroupSize.x)
    if (s_lo[i] <= s_hi[i]) {
      atomicMin(zbins[2u * (first + i)], s_lo[i]);
      atomicMax(zbins[2u * (first + i) + 1u], s_hi[i]);
    }
  // [/zbin-bins]
#elif STEP == 5
  // [zbin-tiles]
  if (g >= lights()) return;
  LightRect l = light_rect(g);  // the tiles its sphere can cover
  int tiles = l.size.x * l.size.y;
  if (tiles > kOwnTiles) {  // a light near the eye: step 6's work groups share its tiles
    wide_lights[atomicAdd(wide_count, 1u)] = g;
    return;
  }
  uint entries = 0u;
  for (int k = 0; k < tiles; ++k) zbin_tile(g, l.c, l.r, l.first + ivec2(k % l.size.x, k / l.size.x), entries);
  // [/zbin-tiles]
  count_entries(entries);
#elif STEP == 6
  // [zbin-wide]
  // The lights step 5 passed on, a work group each (as many as the dispatch has, striding):
  // its invocations take the rectangle's tiles in turn, so that no invocation walks thousands.
  uint entries = 0u;
  for (uint w = gl_WorkGroupID.x; w < wide_count; w += gl_NumWorkGroups.x) {
    uint light = wide_lights[w];
    LightRect l = light_rect(light);
    for (int k = int(gl_LocalInvocationIndex); k < l.size.x * l.size.y; k += int(gl_WorkGroupSize.x))
      zbin_tile(light, l.c, l.r, l.first + ivec2(k % l.size.x, k / l.size.x), entries);
  }
  // [/zbin-wide]
  count_entries(entries);
#endif
}
