#pragma once
// A picture of the grid: each cell's light count on chapter 03's heat ramp, slice by slice
// (slice 0, the nearest, top left; then left to right, top to bottom), each slice a small
// map of the screen's tiles. Empty cells (no surface, or no light) are black.
#include <cstdint>
#include <vector>

#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/09_clustered/cluster_grid.h"
#include "common/gl.h"
#include "common/image.h"

namespace lp::ch09 {

// The picture as an image (rows top down): `full_scale` lights is the ramp's top.
ImageRGBA8 cluster_picture(const Grid& grid, const std::vector<std::uint32_t>& counts, float full_scale);

class ClusterPicture {
 public:
  // Over the whole of `output` (nearest, stretched), replacing the image; with `key_rows`, over
  // all but that many rows at the bottom (cleared), where the key goes.
  void draw(const Grid& grid, const std::vector<std::uint32_t>& counts, const ch03::FrameOutput& output,
            float full_scale = 100.f, int key_rows = 0);

 private:
  gl::Texture texture_{GL_TEXTURE_2D};
  gl::Framebuffer fbo_;
  int width_ = 0, height_ = 0;
};

}  // namespace lp::ch09
