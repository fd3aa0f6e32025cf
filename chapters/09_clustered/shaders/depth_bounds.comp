#version 450
// Pass 1, one work group per screen tile: what depths the G-buffer holds there.
// Tiled: the tile's nearest and farthest view depth (its one cell's range). Clustered: which
// of the tile's depth slices hold any surface (only those get lights assigned). Tiled with
// DEPTH_MASK (Harada's 2.5D culling) then reads the tile again and marks which of 32 equal
// bins of [min, max] hold a surface.
#include "01_forward/shaders/lighting.glsl"
#include "02_gbuffer/shaders/gbuffer.glsl"
#include "09_clustered/shaders/grid.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
// Tiled: per tile (min, max) view depth as float bits (positive floats order like their
// bits); min > max means no surface. Clustered: per cell, 1 where a surface is.
layout(std430, binding = 2) buffer Bounds { uint bounds[]; };

shared uint s_min, s_max, s_mask;

void main() {
  ivec2 tile = ivec2(gl_WorkGroupID.xy);
  ivec2 p0 = tile * u_grid.zw, p1 = min(p0 + u_grid.zw, u_grid.xy);
  if (gl_LocalInvocationIndex == 0u) {
    s_min = 0xFFFFFFFFu;
    s_max = 0u;
    s_mask = 0u;
  }
  barrier();
  // [depth-bounds]
  for (int y = p0.y + int(gl_LocalInvocationID.y); y < p1.y; y += 8)
    for (int x = p0.x + int(gl_LocalInvocationID.x); x < p1.x; x += 8) {
      Surface s = decode_gbuffer(ivec2(x, y));
      if (s.is_sky) continue;
      float d = view_depth(s.position);
#ifdef CLUSTERED
      bounds[cell_index(tile, slice_of(d))] = 1u;  // every writer writes 1: no race to lose
#else
      atomicMin(s_min, floatBitsToUint(d));
      atomicMax(s_max, floatBitsToUint(d));
#endif
    }
  // [/depth-bounds]
#ifndef CLUSTERED
  barrier();
#ifdef DEPTH_MASK
  // [depth-mask-bins]
  float lo = uintBitsToFloat(s_min), hi = uintBitsToFloat(s_max);
  if (s_min <= s_max)
    for (int y = p0.y + int(gl_LocalInvocationID.y); y < p1.y; y += 8)
      for (int x = p0.x + int(gl_LocalInvocationID.x); x < p1.x; x += 8) {
        Surface s = decode_gbuffer(ivec2(x, y));
        if (!s.is_sky) atomicOr(s_mask, 1u << uint(depth_bin(lo, hi, view_depth(s.position))));
      }
  barrier();
  // [/depth-mask-bins]
#endif
  if (gl_LocalInvocationIndex == 0u) {
    int t = tile.y * u_tiles.x + tile.x;
    bounds[kTileBounds * t] = s_min;
    bounds[kTileBounds * t + 1] = s_max;
#ifdef DEPTH_MASK
    bounds[kTileBounds * t + 2] = s_mask;
#endif
  }
#endif
}
