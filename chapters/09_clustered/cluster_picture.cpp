#include "chapters/09_clustered/cluster_picture.h"

#include <algorithm>
#include <cmath>

namespace lp::ch09 {

ImageRGBA8 cluster_picture(const Grid& g, const std::vector<std::uint32_t>& counts, float full_scale) {
  const int cols = int(std::ceil(std::sqrt(double(g.slices)))), rows = (g.slices + cols - 1) / cols;
  const int w = cols * (g.tiles_x + 1) - 1, h = rows * (g.tiles_y + 1) - 1;  // a pixel between slices
  std::vector<float> v(std::size_t(w) * std::size_t(h), 0.f);
  for (int s = 0; s < g.slices; ++s)
    for (int ty = 0; ty < g.tiles_y; ++ty)
      for (int tx = 0; tx < g.tiles_x; ++tx) {
        const std::size_t cell = (std::size_t(s) * g.tiles_y + ty) * g.tiles_x + tx;
        if (cell >= counts.size()) continue;
        const int x = (s % cols) * (g.tiles_x + 1) + tx;
        const int y = (s / cols) * (g.tiles_y + 1) + (g.tiles_y - 1 - ty);  // tile row 0 is the bottom one
        v[std::size_t(y) * w + x] = float(counts[cell]);
      }
  return error_heatmap(v, w, h, full_scale);
}

void ClusterPicture::draw(const Grid& grid, const std::vector<std::uint32_t>& counts, const ch03::FrameOutput& output,
                          float full_scale, int key_rows) {
  ImageRGBA8 img = cluster_picture(grid, counts, full_scale);
  flip_vertically(img);  // OpenGL's first row is the bottom one
  if (img.width != width_ || img.height != height_) {
    texture_ = gl::make_texture_2d(GL_SRGB8_ALPHA8, img.width, img.height);  // sRGB to sRGB: the blit keeps it
    glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT0, texture_.id(), 0);
    width_ = img.width;
    height_ = img.height;
  }
  glTextureSubImage2D(texture_.id(), 0, 0, 0, img.width, img.height, GL_RGBA, GL_UNSIGNED_BYTE, img.pixels.data());
  output.bind();
  glClear(GL_COLOR_BUFFER_BIT);
  const int bottom = std::clamp(key_rows, 0, output.height - 1);  // OpenGL's rows start at the bottom
  glBlitNamedFramebuffer(fbo_.id(), output.framebuffer, 0, 0, img.width, img.height, 0, bottom, output.width, output.height,
                         GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

}  // namespace lp::ch09
