#version 450
// Before zbin_staged.comp shades with lanes (ClusterSettings::lanes_from): which tiles need
// them. One work group a tile counts the bits of the tile's masks (the lights its pixels may
// stage: each met the tile's box) and lists the tile, in the order the groups finish, at the
// front of lane_tiles when it holds at least u_lanes_from lights (heavy: shaded with the
// lanes) or at the back (light: one lane). The two counts are the x of two indirect dispatches.
#include "09_clustered/shaders/grid.glsl"
#include "09_clustered/shaders/zbin.glsl"

layout(local_size_x = 256) in;
uniform uint u_lanes_from;
shared uint s_count;

void main() {
  uint tile = gl_WorkGroupID.y * uint(u_tiles.x) + gl_WorkGroupID.x, t = gl_LocalInvocationIndex;
  if (t == 0u) s_count = 0u;
  barrier();
  // [count-tile]
  // Invocation t takes every 256th word of tile_words; each of its bits names a mask word
  // with bits, whose bits are counted.
  uint count = 0u, words = zbin_word_words();
  for (uint i = t; i < words; i += gl_WorkGroupSize.x) {
    uint set = tile_words[tile * words + i];
    while (set != 0u) {
      uint w = i * 32u + uint(findLSB(set));
      set &= set - 1u;
      count += uint(bitCount(tile_masks[tile * zbin_words() + w]));
    }
  }
  if (count > 0u) atomicAdd(s_count, count);
  barrier();
  if (t != 0u) return;
  if (s_count >= u_lanes_from)
    lane_tiles[atomicAdd(lane_dispatch[0], 1u)] = tile;
  else
    lane_tiles[uint(u_tiles.x * u_tiles.y) - 1u - atomicAdd(lane_dispatch[3], 1u)] = tile;
  // [/count-tile]
}
