#include "chapters/11_temporal/temporal_ao.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"

namespace lp::ch11 {

float ao_turn(unsigned frame) {
  const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
  return float(std::fmod(double(frame) * golden, 2.0 * 3.14159265358979323846));
}

ch07::AoSettings frame_ao(const ch07::AoSettings& ao, const TemporalAoSettings& temporal, unsigned frame) {
  ch07::AoSettings s = ao;
  if (!temporal.enabled) return s;
  s.kernel_parts = std::max(1, temporal.kernel_parts);
  s.kernel_part = int(frame % unsigned(s.kernel_parts));
  if (temporal.turn) s.turn = ao_turn(frame);
  return s;
}

void use_accumulation(ShaderProgram& p, const MotionStage& motion, bool reset, int max_frames, float depth_tolerance,
                      float depth_slope, GLuint history) {
  p.use();
  p.set("u_reset", int(reset));
  p.set("u_max_frames", float(max_frames));
  p.set("u_depth_tolerance", depth_tolerance);
  p.set("u_depth_slope", depth_slope);
  glBindTextureUnit(1, history);
  glBindTextureUnit(2, motion.current());
  glBindTextureUnit(3, reset ? motion.current() : motion.previous());
}

TemporalAoStage::TemporalAoStage(const ch07::AoStage& ao, const MotionStage& motion)
    : ao_(ao), motion_(motion), accumulate_({{GL_COMPUTE_SHADER, "11_temporal/shaders/ao_accumulate.comp"}}) {}

// [temporal-ao-pass]
void TemporalAoStage::before_lights(ch03::DeferredFrame& frame, PassMetrics* metrics) {
  if (!settings_.enabled || !ao_.ran() || !motion_.enabled()) {
    reset_ = true;  // nothing to add to (or no motion to move it by): start again when back
    return;
  }
  if (settings_.max_frames < 1) throw Error("temporal AO: max_frames must be at least 1 (got " + std::to_string(settings_.max_frames) + ")");
  const ch07::Ssao& ssao = ao_.ssao();
  if (ssao.width() != motion_.width() || ssao.height() != motion_.height())
    throw Error("temporal AO: the AO is " + std::to_string(ssao.width()) + "x" + std::to_string(ssao.height()) +
                " and the motion " + std::to_string(motion_.width()) + "x" + std::to_string(motion_.height()) +
                "; accumulate full-resolution AO (AoSettings::scale 1)");
  auto pass = timed(metrics, "temporal AO");
  if (ssao.width() != width_ || ssao.height() != height_) {
    width_ = ssao.width();
    height_ = ssao.height();
    for (gl::Texture& t : history_) t = gl::make_texture_2d(GL_RG32F, width_, height_);
    reset_ = true;
  }
  const bool reset = reset_ || motion_.previous() == 0;
  const int next = 1 - cur_;
  use_accumulation(accumulate_, motion_, reset, settings_.max_frames, settings_.depth_tolerance, settings_.depth_slope,
                   history_[cur_].id());
  // The AO texture the hook reads: this frame's estimate in, the accumulated result out.
  glBindImageTexture(0, ssao.texture(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
  glBindImageTexture(1, history_[next].id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
  glDispatchCompute(GLuint((width_ + 7) / 8), GLuint((height_ + 7) / 8), 1);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  // The frame's G-buffer units are bound again before the lights (bind_hooks): units 1-3 here
  // are ours only for this pass.
  frame.gbuffer().bind_textures();
  cur_ = next;
  reset_ = false;
}
// [/temporal-ao-pass]

}  // namespace lp::ch11
