#version 450
// Pass 2, one work group of 64 per cell: which lights' cut spheres reach the cell's box.
// Each invocation tests a contiguous block of the lights, the work group counts its hits,
// takes that many places from the shared index list with one atomic add, and then writes
// the hits in light order (so every pixel adds its lights in chapter 03's order). The list
// is bounded: a cell that does not fit stores no list and is counted; it is shaded from every
// light (kEveryLight), so no light is lost while the list grows a frame later.
#include "01_forward/shaders/lighting.glsl"
#include "09_clustered/shaders/grid.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 2) readonly buffer Bounds { uint bounds[]; };
// [list-state]
layout(std430, binding = 5) buffer ListState {
  uint head;            // places taken in light_indices
  uint capacity;        // its size
  uint cells_over;      // cells that did not fit: shaded from every light this frame
  uint over_lo, over_hi;  // the entries those cells asked for (64-bit, as fragment_counters.glsl)
  uint needed_lo, needed_hi;    // places every cell together asked for
  uint max_count;       // the longest list
} state;
// [/list-state]

shared uint s_count[64];
shared uint s_offset;
shared bool s_stored;

#ifdef DEPTH_MASK
float g_lo, g_hi;  // the tile's depth bounds and its surfaces' bins (depth_bounds.comp)
uint g_tile_bits;
#endif

bool meets(uint i, Box box) {
  ClusterLight l = cluster_lights[i];
  // [tube-meets]
  // A tube: its capsule against the cell (no depth mask: the bins test a sphere's extent).
  if (int(i) >= u_first_tube)
    return capsule_meets_box((u_view * vec4(l.position_radius.xyz, 1.0)).xyz, (u_view * vec4(l.radiance_inv_range2.xyz, 1.0)).xyz,
                             l.position_radius.w, box, length(u_view[3].xyz));  // the eye's distance from the origin
  // [/tube-meets]
  vec3 centre = (u_view * vec4(l.position_radius.xyz, 1.0)).xyz;
  if (!sphere_meets_box(centre, l.position_radius.w, box)) return false;
#ifdef DEPTH_MASK
  // [depth-mask-test]
  // 2.5D: the light's depth extent must overlap a bin that holds a surface.
  if ((light_depth_bits(g_lo, g_hi, -centre.z, l.position_radius.w) & g_tile_bits) == 0u) return false;
  // [/depth-mask-test]
#endif
  return true;
}

void main() {
  ivec2 tile = ivec2(gl_WorkGroupID.xy);
  int slice = int(gl_WorkGroupID.z);
  int cell = cell_index(tile, slice);
  uint t = gl_LocalInvocationIndex;
  ivec2 p0 = tile * u_grid.zw, p1 = min(p0 + u_grid.zw, u_grid.xy);
#ifdef CLUSTERED
  bool occupied = bounds[cell] != 0u;
  Box box = cell_box(p0, p1, slice_start(slice), slice_start(slice + 1));
#else
  int ti = tile.y * u_tiles.x + tile.x;
  bool occupied = bounds[kTileBounds * ti] <= bounds[kTileBounds * ti + 1];
  Box box = cell_box(p0, p1, uintBitsToFloat(bounds[kTileBounds * ti]), uintBitsToFloat(bounds[kTileBounds * ti + 1]));
#ifdef DEPTH_MASK
  g_lo = uintBitsToFloat(bounds[kTileBounds * ti]);
  g_hi = uintBitsToFloat(bounds[kTileBounds * ti + 1]);
  g_tile_bits = bounds[kTileBounds * ti + 2];
#endif
#endif
#ifdef ALL_CELLS
  occupied = true;  // clustered forward: every cell a forward surface may reach gets its list
#endif
  uint n = occupied ? uint(u_tiles.w) : 0u;
  uint first = n * t / 64u, last = n * (t + 1u) / 64u;  // n <= 2^22 (upload_lights): no overflow

  // [assign]
  uint hits = 0u;
  // (Four lights an iteration: llvmpipe ends a shader's loops after 65 535 iterations in all.)
  for (uint i = first; i < last; i += 4u)
    hits += (meets(i, box) ? 1u : 0u) + (i + 1u < last && meets(i + 1u, box) ? 1u : 0u) +
            (i + 2u < last && meets(i + 2u, box) ? 1u : 0u) + (i + 3u < last && meets(i + 3u, box) ? 1u : 0u);
  s_count[t] = hits;
  barrier();
  if (t == 0u) {  // exclusive prefix sum of the 64 counts, then one allocation for the cell
    uint total = 0u;
    for (int k = 0; k < 64; ++k) {
      uint c = s_count[k];
      s_count[k] = total;
      total += c;
    }
    s_stored = total == 0u;
    s_offset = 0u;
    if (total > 0u) {
      if (atomicAdd(state.needed_lo, total) > 0xFFFFFFFFu - total) atomicAdd(state.needed_hi, 1u);
      atomicMax(state.max_count, total);
      // Take places only while the list has room, so `head` never runs far past capacity.
      if (atomicAdd(state.head, 0u) <= state.capacity) {
        uint offset = atomicAdd(state.head, total);
        s_stored = offset <= state.capacity && total <= state.capacity - offset;
        s_offset = offset;
      }
      if (!s_stored) {
        atomicAdd(state.cells_over, 1u);
        if (atomicAdd(state.over_lo, total) > 0xFFFFFFFFu - total) atomicAdd(state.over_hi, 1u);
      }
    }
    cells[cell] = s_stored ? uvec2(s_offset, total) : uvec2(kEveryLight, uint(u_tiles.w));
  }
  barrier();
  if (!s_stored || hits == 0u) return;
  uint at = s_offset + s_count[t];
  for (uint i = first; i < last; i += 4u) {
    if (meets(i, box)) light_indices[at++] = i;
    if (i + 1u < last && meets(i + 1u, box)) light_indices[at++] = i + 1u;
    if (i + 2u < last && meets(i + 2u, box)) light_indices[at++] = i + 2u;
    if (i + 3u < last && meets(i + 3u, box)) light_indices[at++] = i + 3u;
  }
  // [/assign]
}
