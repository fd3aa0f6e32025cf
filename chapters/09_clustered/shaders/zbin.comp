#version 450
// Z-binning's assignment (zbin.glsl), six dispatches of this file, one STEP each:
//   0 CLEAR:   the last frame's set words of the tiles' masks zeroed, found from tile_words;
//   1 KEYS:    each light's key, its centre's view depth in 16 384 exponential buckets, counted;
//   2 SCAN:    one work group turns the counts into each bucket's first sorted position;
//   3 SCATTER: each light takes a place in its bucket: light_indices is the sorted order;
//   4 BINS:    each sorted light widens the range of every depth bin its extent reaches;
//   5 TILES:   each sorted light sets its bit in the tiles its screen rectangle covers
//              whose boxes (the tile's own depth bounds) its sphere reaches.
// Every step costs what its lights cover (bins, tiles), never lights x tiles. The order
// inside a bucket is the atomics' (it may differ from frame to frame): the lights a pixel
// adds are the same, their float sum may differ by rounding.
#include "09_clustered/shaders/grid.glsl"
#include "09_clustered/shaders/zbin.glsl"

layout(local_size_x = 256) in;
const uint kSortKeys = 16384u;
layout(std430, binding = 8) buffer ZSort {
  uint sort_hist[kSortKeys];  // per bucket: lights, then (SCAN) its next free sorted position
  uint sort_key[];            // per light
};
layout(std430, binding = 2) readonly buffer Bounds { uint bounds[]; };
layout(std430, binding = 5) buffer ListState {
  uint head, capacity, cells_over, over_lo, over_hi, needed_lo, needed_hi, max_count;
} state;

uint lights() { return uint(u_tiles.w); }

#if STEP == 2
shared uint s_sum[256];
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
  light_indices[atomicAdd(sort_hist[sort_key[g]], 1u)] = g;
#elif STEP == 4
  // [zbin-bins]
  if (g >= lights()) return;
  vec4 l = cluster_lights[light_indices[g]].position_radius;
  vec2 e = zbin_extent(view_depth(l.xyz), l.w);
  if (e.y < u_depth_range.x || e.x > u_depth_range.y) return;  // no surface is that near or far
  int b1 = zbin_of(e.y);
  for (int b = zbin_of(e.x); b <= b1; ++b) {
    atomicMin(zbins[2 * b], g);
    atomicMax(zbins[2 * b + 1], g);
  }
  // [/zbin-bins]
#elif STEP == 5
  // [zbin-tiles]
  if (g >= lights()) return;
  vec4 l = cluster_lights[light_indices[g]].position_radius;
  vec3 c = (u_view * vec4(l.xyz, 1.0)).xyz;
  ivec4 rect = sphere_tiles(c, l.w);  // zbin.glsl: the tiles it can cover, empty when nearer than the near plane
  ivec2 t0 = rect.xy, t1 = rect.zw;
  uint word = g / 32u, bit = 1u << (g % 32u), entries = 0u;
  for (int ty = t0.y; ty <= t1.y; ++ty)
    for (int tx = t0.x; tx <= t1.x; ++tx) {
      int ti = ty * u_tiles.x + tx;
      if (bounds[2 * ti] > bounds[2 * ti + 1]) continue;  // no surface in the tile
      ivec2 p0 = ivec2(tx, ty) * u_grid.zw, p1 = min(p0 + u_grid.zw, u_grid.xy);
      Box box = cell_box(p0, p1, uintBitsToFloat(bounds[2 * ti]), uintBitsToFloat(bounds[2 * ti + 1]));
      if (!sphere_meets_box(c, l.w, box)) continue;
      if (atomicOr(tile_masks[uint(ti) * zbin_words() + word], bit) == 0u)  // the word's first bit
        atomicOr(tile_words[uint(ti) * zbin_word_words() + word / 32u], 1u << (word % 32u));
      ++entries;
    }
  // [/zbin-tiles]
#ifndef FLOOR  // (the floor counts its own lists' entries)
  // The list entries, as the other modes count theirs: (tile, light) pairs.
  if (entries > 0u && atomicAdd(state.needed_lo, entries) > 0xFFFFFFFFu - entries) atomicAdd(state.needed_hi, 1u);
#endif
#endif
}
