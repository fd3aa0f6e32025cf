// Z-binning (Drobot, SIGGRAPH 2017), the GLSL shared by its passes (zbin.comp) and its
// shading (shade.glsl with ZBIN). The lights are sorted by the view depth of their centres;
// each depth bin keeps the first and last sorted position of the lights whose depth extent
// reaches it, and each screen tile a bit per sorted light whose sphere reaches the tile's box.
// A pixel evaluates the lights both name: its tile's bits inside its bin's range.
// Needs grid.glsl first. The bins are exponential in depth, as the clustered slices are
// (cluster_grid.h's slice_of with `bins` slices is the C++ twin of zbin_of).
uniform int u_zbins;  // depth bins

// The sorted order: light_indices[p] is the light at sorted position p (grid.glsl's Indices).
// Bin b's range of sorted positions: zbins[2b] the first, zbins[2b + 1] the last (first > last
// when no light reaches it); plain uints, so that every atomic names a scalar.
layout(std430, binding = 6) buffer ZBins { uint zbins[]; };
uvec2 zbin_range(int b) { return uvec2(zbins[2 * b], zbins[2 * b + 1]); }
// Tile t's bit for sorted position p: bit p % 32 of word t * zbin_words() + p / 32.
layout(std430, binding = 7) buffer TileMasks { uint tile_masks[]; };
// Which of a tile's words have any bit set: bit w % 32 of word t * zbin_word_words() + w / 32
// for tile t's word w. The tiles' step sets it with the word's first bit; the next frame's
// clear zeroes only those words (a frame touches a few of a tile's words, not all of them),
// and the shading skips a tile's empty words 32 at a time.
layout(std430, binding = 11) buffer TileWords { uint tile_words[]; };  // (3 is the fragment counters')

#ifdef LANE_TILES
// [lane-tiles]
// ClusterSettings::lanes_from: zbin_lanes.comp's lists of tiles for zbin_staged.comp's two
// indirect dispatches. lane_dispatch[0..2]: the heavy tiles' groups (x, 1, 1), [3..5]: the
// light tiles'. The tiles (y * tiles_x + x): heavy from lane_tiles[0] up, light from
// lane_tiles[tiles - 1] down.
layout(std430, binding = LANE_TILES) buffer LaneTiles {
  uint lane_dispatch[6];
  uint lane_tiles[];
};
// [/lane-tiles]
#endif

// A light and its cone (zero for a point) as the shading reads them.
struct SortedRecord {
  ClusterLight light;
  vec4 cone;
};
#ifdef SORTED_RECORDS
// ClusterSettings::sorted_records: the record at sorted position p, written by the sort
// (zbin.comp's step 3), read by the shading in place of cluster_lights[light_indices[p]].
layout(std430, binding = SORTED_RECORDS) buffer SortedRecords { SortedRecord sorted_records[]; };
#endif

// Word w of a bit array (its positions w * 32 .. w * 32 + 31) cut to the positions first .. last:
// a range's masks (the shading's walk, the staged span) and which of its words have bits.
uint cut_to_span(uint word, uint w, uint first, uint last) {
  if (w == first >> 5u) word &= 0xFFFFFFFFu << (first & 31u);
  if (w == last >> 5u) word &= 0xFFFFFFFFu >> (31u - (last & 31u));
  return word;
}

uint zbin_words() { return (uint(u_tiles.w) + 31u) / 32u; }
uint zbin_word_words() { return (zbin_words() + 31u) / 32u; }

int zbin_of(float d) {
  float t = log(max(d, u_depth_range.x) / u_depth_range.x) / log(u_depth_range.y / u_depth_range.x);
  return clamp(int(floor(t * float(u_zbins))), 0, u_zbins - 1);
}

// A light's depth extent, padded as sphere_meets_box pads its radius and by kDepthPad of its
// depth, so that a surface the light reaches never falls in a bin outside it by rounding.
vec2 zbin_extent(float z, float radius) {
  float r = radius * (1.0 + 1e-5) + 1e-6;
  return vec2((z - r) * (1.0 - kDepthPad), (z + r) * (1.0 + kDepthPad));
}

// [zbin-rect]
// A light's screen rectangle (cluster_grid.h's sphere_tiles, its twin): the pixels (xy lo, zw
// hi; empty when lo > hi) that the sphere (centre in view space, radius) can cover. Its
// view-space box, cut at half the near plane (no surface is nearer), seen from the eye: x / d
// over the box is extreme at its corners, so the rectangle of the corners' projections holds
// the sphere's; a pixel wider on each side for rounding.
vec4 sphere_pixels(vec3 c, float radius) {
  float r = radius * (1.0 + 1e-5) + 1e-6;
  float d0 = max(-c.z - r, 0.5 * u_depth_range.x), d1 = -c.z + r;
  if (d1 < d0) return vec4(1e30, 1e30, -1e30, -1e30);  // wholly nearer than the near plane
  vec2 lo = min((c.xy - r) / d0, (c.xy - r) / d1), hi = max((c.xy + r) / d0, (c.xy + r) / d1);
  vec2 ndc_lo = lo * u_projection.xy - u_projection.zw, ndc_hi = hi * u_projection.xy - u_projection.zw;
  return vec4((ndc_lo * 0.5 + 0.5) * vec2(u_grid.xy) - 1.0, (ndc_hi * 0.5 + 0.5) * vec2(u_grid.xy) + 1.0);
}
// The tiles t0 .. t1 (xy, zw; inclusive, empty when t0 > t1) the sphere's rectangle meets (each
// tile is then tested exactly).
ivec4 sphere_tiles(vec3 c, float radius) {
  vec4 px = sphere_pixels(c, radius);
  if (px.x > px.z) return ivec4(0, 0, -1, -1);  // wholly nearer than the near plane
  vec2 tiles = vec2(u_tiles.xy);
  ivec2 t0 = ivec2(clamp(floor(px.xy / vec2(u_grid.zw)), vec2(0.0), tiles));
  ivec2 t1 = ivec2(clamp(floor(px.zw / vec2(u_grid.zw)), vec2(-1.0), tiles - 1.0));
  return ivec4(t0, t1);
}
// [/zbin-rect]
