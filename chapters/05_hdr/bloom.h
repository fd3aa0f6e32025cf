#pragma once
// Bloom: the glow around very bright things that a real lens adds (diffraction and
// scattering spread a little of every point's light over its neighbours). A bright pass
// keeps what is brighter than a threshold, a chain of 2x reductions brings it to a fraction
// of the resolution, and a separable Gaussian spreads it; the tonemapper samples the result
// with bilinear filtering and adds it, after the curve (the source) or before it.
//
// Level l of the chain has ceil(size / 2^l) texels: an odd size gets a last texel that hangs
// over the edge of the image. Its alpha says what fraction of it the image covers, and the
// next reduction weights by it, so every pixel counts once and the grid stays regular
// (texel i of level l covers pixels [i 2^l, (i + 1) 2^l)) for the bilinear upsampling.
#include <vector>

#include <glm/glm.hpp>

#include "common/gl.h"
#include "common/shader.h"

namespace lp::ch05 {

struct BloomSettings {
  int level = 2;            // blur at 1 / 2^level of the resolution (0: full resolution)
  float radius = 0.02f;     // Gaussian standard deviation, as a fraction of the image height
  float threshold = 1.f;    // exposed luminance above which a pixel blooms
  float limit = 64.f;       // most exposed luminance one pixel gives to the bloom
};

class Bloom {
 public:
  Bloom();
  void reload_shaders();

  // Bright pass of `radiance` x exposure (read from the ExposureState in exposure_buffer),
  // and the reductions to the blur level; then blur() (two calls, so they can be timed apart).
  void bright_pass(GLuint radiance, int width, int height, GLuint exposure_buffer, const BloomSettings& settings);
  void blur(const BloomSettings& settings);

  GLuint bright_texture() const { return chain_.back().id(); }  // at the blur level, before the blur
  GLuint blurred_texture() const { return blurred_.id(); }
  // Maps gl_FragCoord.xy of the full-resolution image to the blur level's texture coordinates.
  glm::vec2 uv_scale() const { return uv_scale_; }
  glm::ivec2 level_size() const { return size_; }
  // The Gaussian's standard deviation in texels of the blur level, and its taps per pass.
  float sigma_texels() const { return sigma_; }
  int taps() const { return 2 * radius_ + 1; }
  std::size_t allocated_bytes() const;

 private:
  void ensure(int width, int height, int level);
  ShaderProgram bright_, downsample_, blur_;
  std::vector<gl::Texture> chain_;  // levels first .. level (first = min(level, 1))
  std::vector<glm::ivec2> sizes_;
  gl::Texture temp_{GL_TEXTURE_2D}, blurred_{GL_TEXTURE_2D};
  int width_ = 0, height_ = 0, level_ = -1;
  glm::ivec2 size_{0};
  glm::vec2 uv_scale_{1};
  float sigma_ = 0;
  int radius_ = 0;
};

// Size of level l of the bloom chain: ceil(n / 2^l).
inline int bloom_level_size(int n, int level) { return (n + (1 << level) - 1) >> level; }

}  // namespace lp::ch05
