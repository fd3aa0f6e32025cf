#include "chapters/11_temporal/temporal_shadows.h"

#include <algorithm>

#include "chapters/11_temporal/temporal_ao.h"
#include "common/error.h"

namespace lp::ch11 {

ch06::ShadowSettings frame_shadows(const ch06::ShadowSettings& shadows, const TemporalShadowSettings& temporal,
                                   unsigned frame) {
  ch06::ShadowSettings s = shadows;
  s.sun_visibility_given = true;  // the stage's pass looks it up before the lights (off: with every tap)
  if (!temporal.enabled) return s;
  s.pcss_parts = std::max(1, temporal.kernel_parts);
  s.pcss_part = int(frame % unsigned(s.pcss_parts));
  if (temporal.turn) s.pcss_turn = ao_turn(frame);
  return s;
}

TemporalShadowStage::TemporalShadowStage(std::function<ch06::ShadowStage*()> shadows, const MotionStage& motion)
    : shadows_(std::move(shadows)), motion_(motion),
      accumulate_({{GL_COMPUTE_SHADER, "11_temporal/shaders/ao_accumulate.comp"}}) {}

// [temporal-shadow-pass]
void TemporalShadowStage::before_lights(ch03::DeferredFrame& frame, PassMetrics* metrics) {
  ran_ = false;
  ch06::ShadowStage* shadows = shadows_ ? shadows_() : nullptr;
  if (!shadows || !shadows->settings().sun_visibility_given) {
    reset_ = true;  // the hook looks the sun up itself: start again when back
    return;
  }
  if (settings_.max_frames < 1)
    throw Error("temporal shadows: max_frames must be at least 1 (got " + std::to_string(settings_.max_frames) + ")");
  const ch02::GBuffer& gbuffer = frame.gbuffer();
  const bool accumulate = settings_.enabled && motion_.enabled();
  if (accumulate && (gbuffer.width() != motion_.width() || gbuffer.height() != motion_.height()))
    throw Error("temporal shadows: the G-buffer is " + std::to_string(gbuffer.width()) + "x" +
                std::to_string(gbuffer.height()) + " and the motion " + std::to_string(motion_.width()) + "x" +
                std::to_string(motion_.height()));
  auto pass = timed(metrics, "temporal shadows");
  if (gbuffer.width() != width_ || gbuffer.height() != height_) {
    width_ = gbuffer.width();
    height_ = gbuffer.height();
    visibility_ = gl::make_texture_2d(GL_R32F, width_, height_);
    radius_ = gl::make_texture_2d(GL_R32F, width_, height_);
    for (gl::Texture& t : history_) t = gl::make_texture_2d(GL_RG32F, width_, height_);
    reset_ = true;
  }
  // 1. This frame's visibility: chapter 06's hook at each pixel, with its part of the disk.
  std::vector<std::string> defines = gbuffer.shader_defines(0);
  for (const std::string& d : shadows->shader_hooks().defines)
    if (d.rfind("SHADOW_SUN_VISIBILITY", 0) != 0) defines.push_back(d);  // the lookup itself, not its result
  if (!visibility_pass_ || defines != visibility_defines_) {
    visibility_pass_ = std::make_unique<ShaderProgram>(
        std::vector<ShaderStage>{{GL_COMPUTE_SHADER, "11_temporal/shaders/sun_visibility.comp"}}, defines);
    visibility_defines_ = defines;
  }
  visibility_pass_->use();
  visibility_pass_->set("u_sun_direction", shadows->sun().direction);
  gbuffer.bind_textures(0);
  shadows->bind_hook_resources();
  glBindImageTexture(0, visibility_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  glBindImageTexture(1, radius_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  glDispatchCompute(GLuint((width_ + 7) / 8), GLuint((height_ + 7) / 8), 1);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  // 2. Blended into the history moved by the motion: the AO's pass (a value and its frames).
  if (accumulate) {
    const bool reset = reset_ || motion_.previous() == 0;
    const int next = 1 - cur_;
    use_accumulation(accumulate_, motion_, reset, settings_.max_frames, settings_.depth_tolerance,
                     settings_.depth_slope, history_[cur_].id());
    glBindImageTexture(0, visibility_.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
    glBindImageTexture(1, history_[next].id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
    glDispatchCompute(GLuint((width_ + 7) / 8), GLuint((height_ + 7) / 8), 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    cur_ = next;
    reset_ = false;
  } else {
    reset_ = true;
  }
  // 3. What the lights read: the result, on the shadow stage's unit (its hook, SHADOW_SUN_VISIBILITY).
  gbuffer.bind_textures(0);  // units 1-3 were the accumulation's for its pass only
  shadows->set_sun_visibility(visibility_.id());
  ran_ = true;
}
// [/temporal-shadow-pass]

}  // namespace lp::ch11
