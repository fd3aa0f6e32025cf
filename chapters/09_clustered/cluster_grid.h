#pragma once
// The cells lights are binned into, and the one test that bins them: a light's cut sphere
// against a cell's box in view space. shaders/grid.glsl is the GLSL twin of this file; the
// unit tests hold this one, the image tests the GLSL one.
//
// A cell is a screen tile (a rectangle of pixels) times a depth range:
// - tiled: one range per tile, the tile's own depth bounds, found from the G-buffer;
// - clustered: `slices` ranges fixed in advance, exponential in depth (Olsson et al. 2012):
//   slice k spans  near * (far / near)^(k / S)  to  near * (far / near)^((k + 1) / S),
//   so every cell is about as deep as it is wide, near and far. With a near slice (Persson's
//   clusters in Just Cause 3, 2015), slice 0 spans near .. near_slice alone and the other S - 1
//   are exponential from near_slice to far: the few metres in front of the camera, where little
//   stands, no longer take half the slices.
#include <cstdint>

#include <glm/glm.hpp>

#include "common/camera.h"

namespace lp::ch09 {

// [grid]
struct Grid {
  int width = 0, height = 0;    // the image, pixels
  int tile_w = 16, tile_h = 16; // a tile, pixels (the last column and row may be cut short)
  int tiles_x = 0, tiles_y = 0; // ceil(width / tile_w), ceil(height / tile_h)
  int slices = 1;               // depth slices (1 for tiled: its range comes from the G-buffer)
  float znear = 0.1f, zfar = 1000.f;  // the camera's, positive view depths
  float near_slice = 0.f;       // clustered: where slice 1 begins (<= znear: no near slice)
  bool has_near_slice() const { return slices > 1 && near_slice > znear && near_slice < zfar; }
  int cells() const { return tiles_x * tiles_y * slices; }
};
// Tiles of `tile_px` square pixels (tiled shading, or clusters of a given tile size).
Grid grid_of_tiles(int width, int height, int tile_px, int slices, float znear, float zfar);
// `nx` x `ny` tiles over the whole image (DOOM 2016's clusters: 16 x 9 x 24).
Grid grid_of_counts(int width, int height, int nx, int ny, int slices, float znear, float zfar);

// The view depth (positive, metres) where slice k begins; slice_start(S) is zfar.
float slice_start(const Grid& g, int k);
// The slice a view depth falls in, clamped to 0 .. slices - 1.
int slice_of(const Grid& g, float view_depth);

// An axis-aligned box in view space (the camera looks down -z).
struct Box {
  glm::vec3 lo, hi;
};
// The box around the part of the view frustum over pixels [x0, x1) x [y0, y1) (OpenGL's
// bottom-left origin) between view depths d0 <= d1, grown by a relative `pad` of its depth
// so that what the shading pass computes for a pixel inside it lies inside it too.
Box cell_box(const FrameCamera& camera, const Grid& g, int x0, int y0, int x1, int y1, float d0, float d1);
// Cell (tx, ty, slice) of a clustered grid.
Box cluster_box(const FrameCamera& camera, const Grid& g, int tx, int ty, int slice);

// Does the sphere (centre in view space, radius) reach the box? Conservative by a relative
// 1e-5 of the radius (plus 1e-6 m), so that a point the shading pass finds exactly at the
// cut distance is never left out by a rounding of the other test.
bool sphere_meets_box(const glm::vec3& centre, float radius, const Box& box);
// [/grid]

// [capsule-box]
// Does a tube's capsule (the segment a-b in view space, radius) reach the box? The segment is
// clipped against the box grown by the radius on every side (a slab test): conservative, since
// the grown box holds the capsule's reach and more at its corners (by up to (sqrt 3 - 1) x the
// radius). Grown further by capsule_rounding_margin, so that float rounding never drops a cell
// the cut reaches. eye_distance: how far the camera is from the world's origin (the view
// transform that made a and b rounded coordinates that large).
bool capsule_meets_box(const glm::vec3& a, const glm::vec3& b, float radius, const Box& box, float eye_distance = 0.f);
// The margin, derived from float rounding. Three computations round what decides whether a
// pixel is within the capsule's cut: the view transform of the tube's ends (a 4-term dot product
// per coordinate, the matrix itself rounded: at most 8 units of roundoff u = 2^-24 of the world
// coordinates' size, the eye's distance plus the view-space size), this slab test (the grown
// bound, the difference and GLSL's 2.5-ulp division: at most 18 u of the size, shown in
// cluster_grid.cpp) and neon_light()'s distance in world space (the closest point's parameter,
// the mix and the length: at most 12 u of the size, sqrt 3 for the length over three axes).
// Their sum, under 8 + 18 + 12 sqrt 3 < 64 units of roundoff of the largest size S any of them
// handles, is the margin: 64 u S. At the street's scale (S of 100 m) it is 0.4 mm.
inline constexpr float kCapsuleRoundingUlps = 64.f;
float capsule_rounding_margin(const glm::vec3& a, const glm::vec3& b, float radius, const Box& box, float eye_distance);
// [/capsule-box]

// Z-binning's screen rectangle of a light (zbin.comp's step 5): the tiles [lo, hi] (inclusive;
// empty when lo > hi) that the sphere (centre in view space, radius) can cover, from its
// view-space box cut at half the near plane, a pixel wider on each side for rounding.
struct TileRect {
  glm::ivec2 lo, hi;
  bool holds(int tx, int ty) const { return tx >= lo.x && tx <= hi.x && ty >= lo.y && ty <= hi.y; }
};
TileRect sphere_tiles(const FrameCamera& camera, const Grid& g, const glm::vec3& centre, float radius);

// Harada's 2.5D culling (Harada, Forward+, 2012) for tiled shading: a tile's depth range
// [lo, hi] is cut into 32 equal bins. The tile's mask has bit b set where one of its surfaces
// lies in bin b; a light's mask has the bins its sphere's depth extent overlaps. A light the
// tile's box lets through is kept only where the two masks share a bit, so a lamp post in
// front of a far wall no longer hands the wall's tile every light in the gap between them.
inline constexpr int kDepthBins = 32;
// The bin of view depth d in [lo, hi] (clamped: depths outside fall in the end bins).
int depth_bin(float lo, float hi, float d);
// Bits of the bins that [d0, d1] overlaps (d0 <= d1).
std::uint32_t depth_range_bits(float lo, float hi, float d0, float d1);
// The light's mask: its centre's view depth z and cut radius, padded as sphere_meets_box is,
// plus kDepthPad of the tile's far depth, so that a surface the light reaches never falls in
// a bin the light's mask leaves out by a rounding of the two computations.
std::uint32_t light_depth_bits(float lo, float hi, float z, float radius);

// The relative depth padding of cell_box (and grid.glsl): far larger than float rounding in
// a view depth (about 1e-7 relative), far smaller than any slice (S <= 256 over 1e6: 5 %).
inline constexpr float kDepthPad = 1e-4f;

}  // namespace lp::ch09
