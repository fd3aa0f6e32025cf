#include "chapters/05_hdr/log_average.h"

#include <algorithm>
#include <cmath>

#include "chapters/05_hdr/hdr_pipeline.h"

namespace lp::ch05 {

namespace {
constexpr int kGroup = 8;  // local size of the image passes
GLuint groups(int n, int per_group) { return GLuint((n + per_group - 1) / per_group); }
}  // namespace

LogAverage::LogAverage()
    : log_pass_({{GL_COMPUTE_SHADER, "05_hdr/shaders/log_luminance.comp"}}),
      log_pass_raw_({{GL_COMPUTE_SHADER, "05_hdr/shaders/log_luminance.comp"}}, {"RAW 1"}),
      downsample_({{GL_COMPUTE_SHADER, "05_hdr/shaders/log_downsample.comp"}}),
      downsample_naive_({{GL_COMPUTE_SHADER, "05_hdr/shaders/log_downsample.comp"}}, {"NAIVE 1"}),
      read_top_({{GL_COMPUTE_SHADER, "05_hdr/shaders/log_read.comp"}}),
      reduce_tiles_({{GL_COMPUTE_SHADER, "05_hdr/shaders/log_reduce.comp"}}, {"STAGE 1"}),
      reduce_partials_({{GL_COMPUTE_SHADER, "05_hdr/shaders/log_reduce.comp"}}, {"STAGE 2"}),
      result_(gl::make_buffer(nullptr, sizeof(LogAverageResult), GL_DYNAMIC_STORAGE_BIT)) {}

void LogAverage::reload_shaders() {
  for (ShaderProgram* p : {&log_pass_, &log_pass_raw_, &downsample_, &downsample_naive_, &read_top_, &reduce_tiles_, &reduce_partials_})
    p->reload();
}

void LogAverage::ensure_chain(int w, int h) {
  if (w == width_ && h == height_) return;
  width_ = w;
  height_ = h;
  // Every level down to 1x1, sized as OpenGL sizes mip levels: max(1, floor(size / 2)).
  levels_ = 1 + int(std::floor(std::log2(double(std::max(w, h)))));
  chain_ = gl::make_texture_2d(GL_RG32F, w, h, levels_);
}

void LogAverage::ensure_partials(std::size_t count) {
  if (count <= partial_capacity_) return;
  partial_capacity_ = count;
  partials_ = gl::make_buffer(nullptr, count * sizeof(Partial));
}

std::size_t LogAverage::allocated_bytes() const {
  std::size_t bytes = 0;
  for (int l = 0, w = width_, h = height_; l < levels_; ++l, w = std::max(1, w / 2), h = std::max(1, h / 2))
    bytes += std::size_t(w) * h * 8;
  return bytes + partial_capacity_ * 8;
}

void LogAverage::compute(GLuint radiance, int w, int h, AverageMethod method, float delta) {
  glBindTextureUnit(0, radiance);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLogAverageBinding, result_.id());
  if (method == AverageMethod::Compute) {
    // [compute-reduction]
    GLuint gx = groups(w, 32), gy = groups(h, 32);  // a workgroup sums a 32x32 tile
    ensure_partials(std::size_t(gx) * gy);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPartialsBinding, partials_.id());
    reduce_tiles_.use();
    reduce_tiles_.set("u_delta", delta);
    glDispatchCompute(gx, gy, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    reduce_partials_.use();
    reduce_partials_.set("u_partial_count", int(gx * gy));
    glDispatchCompute(1, 1, 1);
    // [/compute-reduction]
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    return;
  }

  ensure_chain(w, h);
  // [mip-chain]
  // Level 0: log(delta + L) and a count of 1 per pixel.
  const ShaderProgram& log_pass = method == AverageMethod::MipChain ? log_pass_ : log_pass_raw_;
  log_pass.use();
  log_pass.set("u_delta", delta);
  glBindImageTexture(0, chain_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
  glDispatchCompute(groups(w, kGroup), groups(h, kGroup), 1);
  if (method == AverageMethod::GenerateMipmap) {
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    glGenerateTextureMipmap(chain_.id());  // the source: one call, the driver's box filter
  } else {
    // Then each level from the one below, down to 1x1.
    const ShaderProgram& down = method == AverageMethod::MipChain ? downsample_ : downsample_naive_;
    down.use();
    for (int level = 1, lw = w, lh = h; level < levels_; ++level) {
      lw = std::max(1, lw / 2);
      lh = std::max(1, lh / 2);
      glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
      glBindImageTexture(0, chain_.id(), level - 1, GL_FALSE, 0, GL_READ_ONLY, GL_RG32F);
      glBindImageTexture(1, chain_.id(), level, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
      glDispatchCompute(groups(lw, kGroup), groups(lh, kGroup), 1);
    }
  }
  // [/mip-chain]
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  read_top_.use();
  read_top_.set("u_count_scale", method == AverageMethod::GenerateMipmap ? float(w) * float(h) : 1.f);
  glBindImageTexture(0, chain_.id(), levels_ - 1, GL_FALSE, 0, GL_READ_ONLY, GL_RG32F);
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

LogAverageResult LogAverage::read() const {
  LogAverageResult r{};
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(result_.id(), 0, sizeof(r), &r);
  return r;
}

}  // namespace lp::ch05
