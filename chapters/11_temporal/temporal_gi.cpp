#include "chapters/11_temporal/temporal_gi.h"

#include <algorithm>

#include "chapters/11_temporal/temporal_ao.h"
#include "common/error.h"

namespace lp::ch11 {

ch08::GiSettings frame_gi(const ch08::GiSettings& gi, const TemporalGiSettings& temporal, unsigned frame) {
  ch08::GiSettings s = gi;
  if (!temporal.enabled) return s;
  s.samples = temporal.samples;
  s.kernel_parts = std::max(1, temporal.kernel_parts);
  s.kernel_part = int(frame % unsigned(s.kernel_parts));
  if (temporal.turn) s.turn = ao_turn(frame);
  s.keep_transfer = true;  // the accumulation clamps its sums, not each frame's (gi_accumulate.comp)
  return s;
}

TemporalGiStage::TemporalGiStage(const MotionStage& motion)
    : motion_(motion), accumulate_({{GL_COMPUTE_SHADER, "11_temporal/shaders/gi_accumulate.comp"}}) {}

// [temporal-gi-pass]
void TemporalGiStage::filter(ch03::DeferredFrame& frame, const ch08::Ssgi& ssgi, PassMetrics* metrics) {
  ran_ = false;
  if (!settings_.enabled || !motion_.enabled()) {
    reset_ = true;  // nothing to add to (or no motion to move it by): start again when back
    return;
  }
  if (settings_.max_frames < 1) throw Error("temporal GI: max_frames must be at least 1 (got " + std::to_string(settings_.max_frames) + ")");
  if (ssgi.width() != motion_.width() || ssgi.height() != motion_.height())
    throw Error("temporal GI: the pass is " + std::to_string(ssgi.width()) + "x" + std::to_string(ssgi.height()) +
                " and the motion " + std::to_string(motion_.width()) + "x" + std::to_string(motion_.height()) +
                "; accumulate without a guard band");
  if (!ssgi.transfer())
    throw Error("temporal GI: chapter 08's pass kept no transfer totals (GiSettings::keep_transfer; frame_gi sets it)");
  auto pass = timed(metrics, "temporal AO + indirect");
  if (ssgi.width() != width_ || ssgi.height() != height_) {
    width_ = ssgi.width();
    height_ = ssgi.height();
    for (int k = 0; k < 2; ++k) {
      history_[k] = gl::make_texture_2d(GL_RGBA32F, width_, height_);
      frames_[k] = gl::make_texture_2d(GL_RG32F, width_, height_);
    }
    reset_ = true;
  }
  const bool reset = reset_ || motion_.previous() == 0;
  const int next = 1 - cur_;
  use_accumulation(accumulate_, motion_, reset, settings_.max_frames, settings_.depth_tolerance, settings_.depth_slope,
                   history_[cur_].id());
  glBindTextureUnit(4, frames_[cur_].id());
  // Chapter 08's result, which the light buffer adds next: this frame's in, the accumulated out.
  glBindImageTexture(0, ssgi.texture(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
  glBindImageTexture(1, history_[next].id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glBindImageTexture(2, frames_[next].id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
  glBindImageTexture(3, ssgi.transfer(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
  glDispatchCompute(GLuint((width_ + 7) / 8), GLuint((height_ + 7) / 8), 1);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  frame.gbuffer().bind_textures();  // units 1-4 were ours for this pass only
  cur_ = next;
  reset_ = false;
  ran_ = true;
}
// [/temporal-gi-pass]

}  // namespace lp::ch11
