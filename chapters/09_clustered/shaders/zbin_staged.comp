#version 450
#ifdef PHASE_CLOCKS
#extension GL_ARB_shader_clock : require
#endif
// Pass 3 of Z-binning with the tile's lights staged in shared memory: one work group per
// tile, one invocation per pixel. The group takes the sorted positions its pixels' depth bins
// name (the union of their ranges), copies the lights of that span whose tile bit is set into
// shared memory, a chunk at a time and in sorted order, and each pixel adds the chunk's lights
// that lie in its own bin's range. The same lights in the same order as zbin_visit (shade.glsl)
// adds them, each record read from memory once per tile instead of once per pixel. With
// PIXEL_LANES (ClusterSettings::pixel_lanes) a pixel has that many invocations, the group's
// z: each adds every PIXEL_LANES-th of the pixel's lights, and lane 0 adds up the lanes' sums.
// With FLOOR_LISTS (zbin-floor's assignment) the pass lights nothing: it writes each pixel's
// exact list, the staged lights whose cut reaches its surface (floor_lists() below).
#ifndef PIXEL_LANES
#define PIXEL_LANES 1
#endif
layout(local_size_x = STAGE_TILE, local_size_y = STAGE_TILE, local_size_z = PIXEL_LANES) in;
#define FRAME_PIXEL_COMPUTE 1  // the frame's hooks read this invocation's pixel,
#define FRAME_PIXEL_REMAPPED 1  // which invocation_pixel() below names
#include "09_clustered/shaders/shade.glsl"

// Every loop here counts against llvmpipe's limit of 65 535 iterations a shader (see the lists'
// loop): the pixel's loop adds four lights an iteration, the searches have fixed steps.
#ifndef FLOOR_LISTS
layout(binding = LIGHT_BUFFER_IMAGE + 0, rgba16f) uniform image2D u_l1;  // LightBuffer::image_defines()
layout(binding = LIGHT_BUFFER_IMAGE + 1, rgba16f) uniform image2D u_l2;
#endif

const uint kPixels = uint(STAGE_TILE * STAGE_TILE), kLanes = uint(PIXEL_LANES);
const uint kGroup = kPixels * kLanes;  // invocations: lane j's are kPixels * j onwards
// Records staged at once: 256 (12 KiB of records; GL promises 32 KiB of shared memory), or
// the group's size where that is smaller (8-pixel tiles: 64).
const uint kChunk = min(kGroup, 256u);
shared uint s_first, s_last;   // the span of sorted positions the tile's pixels name
shared uint s_sum[kGroup];     // the words' bit counts, summed (each invocation's word's end)
shared int s_light[kChunk];
shared uint s_position[kChunk];  // ascending within a chunk, and from chunk to chunk
// The staged records: an array of records, or (ClusterSettings::staged_fields) an array per
// field, a structure of arrays. The same values either way; only their layout differs.
#if defined(FLOOR_LISTS)  // the floor's lists test the cut alone: the positions and radii
shared vec4 s_position_radius[kChunk];
void stage_record(uint k, SortedRecord r) { s_position_radius[k] = r.light.position_radius; }
SortedRecord staged_record(uint k) { return SortedRecord(ClusterLight(s_position_radius[k], vec4(0.0)), vec4(0.0)); }
#elif defined(STAGED_FIELDS)
shared vec4 s_position_radius[kChunk], s_radiance[kChunk], s_cone[kChunk];
void stage_record(uint k, SortedRecord r) {
  s_position_radius[k] = r.light.position_radius;
  s_radiance[k] = r.light.radiance_inv_range2;
  s_cone[k] = r.cone;
}
SortedRecord staged_record(uint k) { return SortedRecord(ClusterLight(s_position_radius[k], s_radiance[k]), s_cone[k]); }
#else
shared SortedRecord s_record[kChunk];
void stage_record(uint k, SortedRecord r) { s_record[k] = r; }
SortedRecord staged_record(uint k) { return s_record[k]; }
#endif

// The group's tile: the dispatch's grid is the tiles' (x, y), or with LANE_TILES the group takes
// its tile from zbin_lanes.comp's list, the heavy tiles' from the front (TILES_FROM_END 0), the
// light tiles' from the back (1).
#ifdef LANE_TILES
ivec2 group_tile() {
  uint k = TILES_FROM_END != 0 ? uint(u_tiles.x * u_tiles.y) - 1u - gl_WorkGroupID.x : gl_WorkGroupID.x;
  uint tile = lane_tiles[k];
  return ivec2(tile % uint(u_tiles.x), tile / uint(u_tiles.x));
}
#else
ivec2 group_tile() { return ivec2(gl_WorkGroupID.xy); }
#endif
// The tile's first pixel.
ivec2 tile_origin() { return group_tile() * STAGE_TILE; }

#ifdef SUB_BLOCKS
// ClusterSettings::sub_blocks: the tile cut into blocks of 8 x 4 pixels, one to each 32
// invocations (a warp on NVIDIA's GPUs), each with its own depth bounds and box. A staged light
// carries a bit per block its sphere meets, and a block's pixels pass over the lights whose
// bit is clear together: a warp skips a light whole instead of idling beside a lane that adds it.
const uint kBlockW = 8u, kBlockH = 4u;
const uint kBlockPixels = kBlockW * kBlockH;  // a block's invocations
const uint kBlockColumns = uint(STAGE_TILE) / kBlockW, kBlocks = kPixels / kBlockPixels;
shared uint s_block_near[kBlocks], s_block_far[kBlocks];  // view depths as uint bits (positive floats order alike)
shared vec3 s_block_lo[kBlocks], s_block_hi[kBlocks];
shared uint s_blocks;  // the blocks that hold a surface
shared uint s_reach[kChunk];  // each staged light's blocks
uint block_of(uint t) { return t / kBlockPixels; }  // invocation t's block
// Invocation t's pixel in the tile: its block's, in rows of 8.
uvec2 local_pixel(uint t) {
  uint b = block_of(t), i = t % kBlockPixels;
  return uvec2((b % kBlockColumns) * kBlockW + i % kBlockW, (b / kBlockColumns) * kBlockH + i / kBlockW);
}
// Which of the blocks b0, b0 + step, ... a light (world-space centre, radius) meets. A cheap
// test first, the light's screen rectangle (sphere_pixels, in blocks) and depth extent
// (zbin_extent) against the block's pixels and depth bounds; then the tile's own test
// (sphere_meets_box) on the block's box, which is tighter.
uint blocks_reached(vec4 position_radius, uint b0, uint step) {
  vec3 c = (u_view * vec4(position_radius.xyz, 1.0)).xyz;
  vec2 extent = zbin_extent(-c.z, position_radius.w);
  vec4 px = sphere_pixels(c, position_radius.w) - vec2(tile_origin()).xyxy;
  vec2 size = vec2(kBlockW, kBlockH);  // clamped so that the conversion cannot overflow
  ivec4 rect = ivec4(clamp(floor(px / size.xyxy), vec4(-1.0), vec4(64.0)));
  uint reach = 0u;
  for (uint b = b0; b < kBlocks; b += step) {
    ivec2 at = ivec2(b % kBlockColumns, b / kBlockColumns);
    bool covered = all(greaterThanEqual(at, rect.xy)) && all(lessThanEqual(at, rect.zw));
    bool deep = uintBitsToFloat(s_block_near[b]) <= extent.y && uintBitsToFloat(s_block_far[b]) >= extent.x;
    if (covered && deep && (s_blocks & (1u << b)) != 0u &&
        sphere_meets_box(c, position_radius.w, Box(s_block_lo[b], s_block_hi[b])))
      reach |= 1u << b;
  }
  return reach;
}
#else
uvec2 local_pixel(uint t) {
  t %= kPixels;  // the pixel of each lane
  return uvec2(t % uint(STAGE_TILE), t / uint(STAGE_TILE));
}
#endif
// The pixel of this invocation (the frame's hooks read it: frame_pixel.glsl).
ivec2 invocation_pixel() { return tile_origin() + ivec2(local_pixel(gl_LocalInvocationIndex)); }

// [phase-clocks]
#ifdef PHASE_CLOCKS
// ClusterSettings::phase_clocks, a benchmark: where a work group's time goes. Invocation 0 reads
// its SM's clock after each phase (each ends at a barrier, so its reading is the group's) and
// adds the cycles since its last reading to the phase's sum: ClusteredLights::phase_names().
layout(std430, binding = PHASE_CLOCKS) buffer PhaseClocks { uint phase_cycles[]; };  // phase k: [2k] low, [2k + 1] high
const int kPhases = 6;
uint clock_at, clock_sums[kPhases];
void clock_start() {
  clock_at = clock2x32ARB().x;
  for (int k = 0; k < kPhases; ++k) clock_sums[k] = 0u;
}
void clock_phase(int k) {
  uint now = clock2x32ARB().x;
  clock_sums[k] += now - clock_at;  // unsigned: right across the counter's wrap
  clock_at = now;
}
void clock_add() {  // into the 64-bit sums: a carry where the low word wraps
  if (gl_LocalInvocationIndex != 0u) return;
  for (int k = 0; k < kPhases; ++k) {
    uint before = atomicAdd(phase_cycles[2 * k], clock_sums[k]);
    if (before + clock_sums[k] < before) atomicAdd(phase_cycles[2 * k + 1], 1u);
  }
}
#else
void clock_start() {}
void clock_phase(int k) {}
void clock_add() {}
#endif
const int kSetup = 0, kSpan = 1, kStage = 2, kReach = 3, kShade = 4, kOutput = 5;  // the phases
// [/phase-clocks]

// [zbin-stage]
// Invocation t's mask word of this round, cut to the span: each round takes kGroup words.
uint span_word(uint tile, uint w, uint first, uint last) {
  if (w > (last >> 5u)) return 0u;
  if ((tile_words[tile * zbin_word_words() + (w >> 5u)] & (1u << (w & 31u))) == 0u) return 0u;  // no bit set
  return cut_to_span(tile_masks[tile * zbin_words() + w], w, first, last);
}

// Inclusive prefix sums of s_sum over the group (Hillis and Steele: log2 kGroup steps).
void sum_up(uint t) {
  for (uint o = 1u; o < kGroup; o <<= 1u) {
    uint v = t >= o ? s_sum[t - o] : 0u;
    barrier();
    s_sum[t] += v;
    barrier();
  }
}

// How many of the chunk's first n staged lights lie before sorted position p (a binary search
// with a fixed number of steps: the positions ascend). Its steps are powers of two, from the
// largest within kChunk: they sum to any count up to kChunk (12-pixel tiles: 144).
uint staged_before(uint p, uint n) {
  uint a = 0u;
  for (uint step = 1u << uint(findMSB(kChunk)); step > 0u; step >>= 1u)
    if (a + step <= n && s_position[a + step - 1u] < p) a += step;
  return a;
}

// Staged light k added to the pixel's sums, unless (with the blocks) it cannot reach the
// pixel's block; `evaluated` counts those added.
void add_staged(Surface s, vec3 to_eye, uint k, uint block_bit, inout vec3 diffuse, inout vec3 specular,
                inout uint evaluated, inout uint lit) {
#ifdef SUB_BLOCKS
  if ((s_reach[k] & block_bit) == 0u) return;
#endif
  SortedRecord r = staged_record(k);
  add_lamp(s, to_eye, s_light[k], r.light, r.cone, diffuse, specular, lit);
  ++evaluated;
}

// What the walk does with each light of a pixel's part: add it (the shading), or (the floor's
// lists) count those whose cut reaches the surface, or write them from `entry` on.
const int kAdd = 0, kCount = 1, kWrite = 2;
#ifdef FLOOR
void list_staged(Surface s, uint k, int op, inout uint entry) {
  if (!cut_reaches(staged_record(k).light.position_radius, s)) return;
  if (op == kWrite) floor_lights[entry] = uint(s_light[k]);
  ++entry;
}
#else
void list_staged(Surface s, uint k, int op, inout uint entry) {}
#endif
void visit_staged(Surface s, vec3 to_eye, uint k, uint block_bit, int op, inout uint entry, inout vec3 diffuse,
                  inout vec3 specular, inout uint evaluated, inout uint lit) {
  if (op == kAdd)
    add_staged(s, to_eye, k, block_bit, diffuse, specular, evaluated, lit);
  else
    list_staged(s, k, op, entry);
}
// [/zbin-stage]

// [pixel-lanes]
#if PIXEL_LANES > 1
shared vec3 s_lane_diffuse[kPixels], s_lane_specular[kPixels];
shared uvec2 s_lane_counts[kPixels];  // evaluated, lit
#endif
// The lanes' sums into lane 0's, in lane order (a fixed order: the same image every frame).
void add_lanes(uint lane, uint pixel, inout vec3 diffuse, inout vec3 specular, inout uint evaluated, inout uint lit) {
#if PIXEL_LANES > 1
  for (uint j = 1u; j < kLanes; ++j) {
    if (lane == j) {
      s_lane_diffuse[pixel] = diffuse;
      s_lane_specular[pixel] = specular;
      s_lane_counts[pixel] = uvec2(evaluated, lit);
    }
    barrier();
    if (lane == 0u) {
      diffuse += s_lane_diffuse[pixel];
      specular += s_lane_specular[pixel];
      evaluated += s_lane_counts[pixel].x;
      lit += s_lane_counts[pixel].y;
    }
    barrier();
  }
#endif
}
// [/pixel-lanes]

// [zbin-staged-loop]
// The tile's span walked: its lights staged a chunk at a time, and each pixel's part of each
// chunk visited (op: kAdd, or the floor's kCount and kWrite). Every invocation of the group
// calls it with the same span: its barriers are uniform.
void walk_span(int op, uint tile, uint first, uint last, Surface s, vec3 to_eye, uvec2 range, uint lane, uint block_bit,
               inout uint entry, inout vec3 diffuse, inout vec3 specular, inout uint evaluated, inout uint lit) {
  uint t = gl_LocalInvocationIndex;
  if (first <= last)
    for (uint w0 = first >> 5u; w0 <= last >> 5u; w0 += kGroup) {
      // A round: invocation t's word, its lights counted and numbered in sorted order.
      uint m = span_word(tile, w0 + t, first, last);
      barrier();  // the last round's total is read
      s_sum[t] = uint(bitCount(m));
      barrier();
      sum_up(t);
      uint total = s_sum[kGroup - 1u], before = s_sum[t] - uint(bitCount(m));
      clock_phase(kSpan);
      // The round's lights in chunks of kChunk: each invocation stages those of its word that
      // fall in the chunk, then every pixel adds those in its own range.
      for (uint chunk = 0u; chunk < total; chunk += kChunk) {
        uint at = before, bits = before + uint(bitCount(m)) > chunk ? m : 0u;  // (a word before the chunk: none)
        while (bits != 0u && at < chunk + kChunk) {
          uint p = (w0 + t) * 32u + uint(findLSB(bits));
          bits &= bits - 1u;
          if (at >= chunk) {
            int i = int(light_indices[p]);
            stage_record(at - chunk, zbin_record(p, i));
            s_light[at - chunk] = i;
            s_position[at - chunk] = p;
#ifdef SUB_BLOCKS
            s_reach[at - chunk] = 0u;
#endif
          }
          ++at;
        }
        barrier();
        clock_phase(kStage);
        uint n = min(kChunk, total - chunk);  // the lights staged
#ifdef SUB_BLOCKS
        // Each light's blocks: kGroup / kChunk invocations a light (32-pixel tiles: four), each
        // taking every fourth block.
        if (t % kChunk < n) {
          uint reach = blocks_reached(staged_record(t % kChunk).light.position_radius, t / kChunk, kGroup / kChunk);
          if (reach != 0u) atomicOr(s_reach[t % kChunk], reach);
        }
        barrier();
        clock_phase(kReach);
#endif
        // [zbin-staged-pixel]
        // The pixel's part of the chunk: its lights from the range's start to its end (none
        // where its bin's range is empty, x > y: then b <= a), this lane's every kLanes-th.
        uint a = staged_before(range.x, n), b = staged_before(range.y + 1u, n);
        for (uint k = a + lane; k < b; k += 4u * kLanes) {
          visit_staged(s, to_eye, k, block_bit, op, entry, diffuse, specular, evaluated, lit);
          if (k + kLanes < b) visit_staged(s, to_eye, k + kLanes, block_bit, op, entry, diffuse, specular, evaluated, lit);
          if (k + 2u * kLanes < b) visit_staged(s, to_eye, k + 2u * kLanes, block_bit, op, entry, diffuse, specular, evaluated, lit);
          if (k + 3u * kLanes < b) visit_staged(s, to_eye, k + 3u * kLanes, block_bit, op, entry, diffuse, specular, evaluated, lit);
        }
        // [/zbin-staged-pixel]
        barrier();  // the chunk is read before the next is staged
        clock_phase(kShade);
      }
    }
}
// [/zbin-staged-loop]

#ifdef FLOOR_LISTS
// [floor-lists]
// zbin-floor's assignment: each pixel's exact list, the lights of its part of the span whose
// cut reaches its surface, in the index list. Two walks: the first counts each (pixel, lane)'s
// lights, a prefix sum over the group places them (a pixel's lanes one after another) and one
// atomic takes the tile's room; the second writes them. Bounded as the index list is: a tile
// that does not fit marks its pixels (kEveryLight: shaded through Z-binning) and is counted.
layout(std430, binding = 5) buffer ListState {
  uint head, capacity, cells_over, over_lo, over_hi, needed_lo, needed_hi, max_count;
} state;
shared uint s_base, s_stored, s_pixels, s_longest;
void floor_lists(uint tile, uint first, uint last, Surface s, uvec2 range, uint lane, bool inside, ivec2 pixel) {
  uint t = gl_LocalInvocationIndex, u = (t % kPixels) * kLanes + lane;  // (pixel, lane) order
  vec3 no_light = vec3(0.0);
  uint n = 0u, unused = 0u;
  walk_span(kCount, tile, first, last, s, vec3(0.0), range, lane, 0u, n, no_light, no_light, unused, unused);
  if (t == 0u) s_pixels = s_longest = 0u;
  barrier();  // every invocation has read the walk's last round total (s_sum) before it is reused
  s_sum[u] = n;
  barrier();
  sum_up(t);
  uint total = s_sum[kGroup - 1u], start = s_sum[u] - n;  // the tile's entries; this (pixel, lane)'s first
  uint count = lane == 0u ? s_sum[u + kLanes - 1u] - start : 0u;  // the pixel's, its lanes' together
  if (count > 0u) {
    atomicAdd(s_pixels, 1u);
    atomicMax(s_longest, count);
  }
  if (t == 0u) {
    uint base = 0u;
    bool stored = true;
    if (total > 0u) {
      if (atomicAdd(state.needed_lo, total) > 0xFFFFFFFFu - total) atomicAdd(state.needed_hi, 1u);
      stored = false;
      if (atomicAdd(state.head, 0u) <= state.capacity) {
        base = atomicAdd(state.head, total);
        stored = base <= state.capacity && total <= state.capacity - base;
      }
    }
    s_base = base;
    s_stored = stored ? 1u : 0u;
  }
  barrier();
  bool stored = s_stored != 0u;  // the same in every invocation
  if (t == 0u && total > 0u) {
    atomicMax(state.max_count, s_longest);
    if (!stored) {
      atomicAdd(state.cells_over, s_pixels);
      if (atomicAdd(state.over_lo, total) > 0xFFFFFFFFu - total) atomicAdd(state.over_hi, 1u);
    }
  }
  if (inside && lane == 0u)
    cells[pixel.y * u_grid.x + pixel.x] = count == 0u ? uvec2(0u) : stored ? uvec2(s_base + start, count) : uvec2(kEveryLight, 0u);
  if (!stored || total == 0u) return;
  uint entry = s_base + start;
  walk_span(kWrite, tile, first, last, s, vec3(0.0), range, lane, 0u, entry, no_light, no_light, unused, unused);
}
// [/floor-lists]
#endif

void main() {
  clock_start();
  uint t = gl_LocalInvocationIndex, lane = t / kPixels;  // (lane 0 alone without PIXEL_LANES)
  ivec2 pixel = invocation_pixel();
  bool inside = all(lessThan(pixel, u_grid.xy));
  Surface s = decode_gbuffer(inside ? pixel : ivec2(0));
  bool shaded = inside && !s.is_sky;
  uint tile = uint(cell_index(group_tile(), 0));  // the group's tile (STAGE_TILE pixels)
  if (t == 0u) {
    s_first = 0xFFFFFFFFu;
    s_last = 0u;
  }
  uint block_bit = 0u;
#ifdef SUB_BLOCKS
  uint block = block_of(t);
  block_bit = 1u << block;
  if (t < kBlocks) {
    s_block_near[t] = floatBitsToUint(u_depth_range.y * 2.0);
    s_block_far[t] = 0u;
  }
  if (t == 0u) s_blocks = 0u;
#endif
  barrier();
  // The pixel's range of sorted positions (zbin_visit's), and the tile's: their union.
  float depth = view_depth(s.position);
  uvec2 range = shaded ? zbin_range(zbin_of(depth)) : uvec2(1u, 0u);
  if (range.x <= range.y) {
    atomicMin(s_first, range.x);
    atomicMax(s_last, range.y);
  }
#ifdef SUB_BLOCKS
  if (shaded) {  // the block's depth bounds, as depth_bounds.comp takes a tile's
    atomicMin(s_block_near[block], floatBitsToUint(max(depth, 0.0)));
    atomicMax(s_block_far[block], floatBitsToUint(max(depth, 0.0)));
    atomicOr(s_blocks, block_bit);
  }
  barrier();
  if (t < kBlocks && (s_blocks & (1u << t)) != 0u) {  // each block's box (cell_box, the tile's)
    ivec2 p0 = tile_origin() + ivec2(t % kBlockColumns, t / kBlockColumns) * ivec2(kBlockW, kBlockH);
    Box box = cell_box(p0, min(p0 + ivec2(kBlockW, kBlockH), u_grid.xy), uintBitsToFloat(s_block_near[t]), uintBitsToFloat(s_block_far[t]));
    s_block_lo[t] = box.lo;
    s_block_hi[t] = box.hi;
  }
#endif
  barrier();
  clock_phase(kSetup);
  uint first = s_first, last = s_last;  // the same in every invocation: the loops below are uniform
#ifdef FLOOR_LISTS
  floor_lists(tile, first, last, s, range, lane, inside, pixel);
#else
  vec3 diffuse = vec3(0.0), specular = vec3(0.0);
  vec3 to_eye = normalize(gb_eye.xyz - s.position);
  uint evaluated = 0u, lit = 0u, unused = 0u;
  walk_span(kAdd, tile, first, last, s, to_eye, range, lane, block_bit, unused, diffuse, specular, evaluated, lit);
  add_lanes(lane, t % kPixels, diffuse, specular, evaluated, lit);
  if (!inside || lane != 0u) return;
  if (shaded) count_pixel(evaluated, lit);
  vec4 l1, l2;
  output_of(diffuse, specular, evaluated, lit, l1, l2);
  imageStore(u_l1, pixel, imageLoad(u_l1, pixel) + l1);
  imageStore(u_l2, pixel, imageLoad(u_l2, pixel) + l2);
  clock_phase(kOutput);
  clock_add();
#endif
}
