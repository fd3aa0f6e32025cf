#include "chapters/05_hdr/bloom.h"

#include <algorithm>
#include <cmath>

#include "chapters/05_hdr/hdr_pipeline.h"

namespace lp::ch05 {

namespace {
constexpr int kGroup = 8;
GLuint groups(int n) { return GLuint((n + kGroup - 1) / kGroup); }
}  // namespace

Bloom::Bloom()
    : bright_({{GL_COMPUTE_SHADER, "05_hdr/shaders/bloom_bright.comp"}}),
      downsample_({{GL_COMPUTE_SHADER, "05_hdr/shaders/bloom_downsample.comp"}}),
      blur_({{GL_COMPUTE_SHADER, "05_hdr/shaders/bloom_blur.comp"}}) {}

void Bloom::reload_shaders() {
  bright_.reload();
  downsample_.reload();
  blur_.reload();
}

void Bloom::ensure(int w, int h, int level) {
  if (w == width_ && h == height_ && level == level_) return;
  width_ = w;
  height_ = h;
  level_ = level;
  chain_.clear();
  sizes_.clear();
  for (int l = std::min(level, 1); l <= level; ++l) {
    sizes_.push_back({bloom_level_size(w, l), bloom_level_size(h, l)});
    chain_.push_back(gl::make_texture_2d(GL_RGBA16F, sizes_.back().x, sizes_.back().y));
  }
  size_ = sizes_.back();
  temp_ = gl::make_texture_2d(GL_RGBA16F, size_.x, size_.y);
  blurred_ = gl::make_texture_2d(GL_RGBA16F, size_.x, size_.y);
  uv_scale_ = 1.f / (float(1 << level) * glm::vec2(size_));
}

std::size_t Bloom::allocated_bytes() const {
  std::size_t bytes = 2 * std::size_t(size_.x) * size_.y * 8;
  for (auto s : sizes_) bytes += std::size_t(s.x) * s.y * 8;
  return bytes;
}

void Bloom::bright_pass(GLuint radiance, int w, int h, GLuint exposure_buffer, const BloomSettings& s) {
  ensure(w, h, s.level);
  // [bloom-chain]
  // Bright pass straight into level 1 (each texel: the mean of its 2x2 pixels), or level 0
  // for a full-resolution bloom.
  glBindTextureUnit(0, radiance);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kExposureBinding, exposure_buffer);
  bright_.use();
  bright_.set("u_footprint", s.level == 0 ? 1 : 2);
  bright_.set("u_threshold", s.threshold);
  bright_.set("u_limit", s.limit);
  glBindImageTexture(0, chain_[0].id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  glDispatchCompute(groups(sizes_[0].x), groups(sizes_[0].y), 1);
  // Then halve until the blur level, weighting each texel by how much of it is image.
  downsample_.use();
  for (std::size_t i = 1; i < chain_.size(); ++i) {
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glBindImageTexture(0, chain_[i - 1].id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA16F);
    glBindImageTexture(1, chain_[i].id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute(groups(sizes_[i].x), groups(sizes_[i].y), 1);
  }
  // [/bloom-chain]
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void Bloom::blur(const BloomSettings& s) {
  // [bloom-blur]
  // The radius is a fraction of the image height, so the look does not change with the
  // resolution; at level l it spans 2^l times fewer texels.
  sigma_ = s.radius * float(height_) / float(1 << s.level);
  radius_ = sigma_ > 0.01f ? int(std::ceil(3.f * sigma_)) : 0;
  blur_.use();
  blur_.set("u_sigma", std::max(sigma_, 0.01f));
  blur_.set("u_radius", radius_);
  const GLuint passes[2][2] = {{chain_.back().id(), temp_.id()}, {temp_.id(), blurred_.id()}};
  for (int pass = 0; pass < 2; ++pass) {  // horizontal, then vertical
    blur_.set("u_horizontal", int(pass == 0));
    glBindImageTexture(0, passes[pass][0], 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA16F);
    glBindImageTexture(1, passes[pass][1], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute(groups(size_.x), groups(size_.y), 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }
  // [/bloom-blur]
}

}  // namespace lp::ch05
