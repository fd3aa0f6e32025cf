#pragma once
// Chapter 06's PCSS accumulated over frames, as temporal_ao.h does chapter 07's AO: each frame
// the sun's visibility is looked up with few taps (the next part of PCSS's Poisson disk, for the
// blocker search and for the filter, the disk turned by the frame's angle), one value a pixel of
// the G-buffer, and blended into the last frames' moved by the motion vectors, dropping the history
// where the surface was hidden last frame (shaders/disocclusion.glsl). A stage of chapter 03's
// frame after chapter 06's ShadowStage and the MotionStage: the light passes read its result
// instead of looking up the map (ShadowSettings::sun_visibility_given).
//
//   frame.add_stage(shadows); frame.add_stage(motion); frame.add_stage(temporal);
//   shadows.set(frame_shadows(pcss, temporal_settings, i)); temporal.set(temporal_settings);
//   if (cut) temporal.reset();
#include <functional>

#include "chapters/06_shadows/shadow_stage.h"
#include "chapters/11_temporal/motion.h"

namespace lp::ch11 {

// [temporal-shadow-settings]
struct TemporalShadowSettings {
  bool enabled = true;            // off: this frame's part alone, nothing accumulated
  int max_frames = 4;             // this frame weighs at least 1 / max_frames (the AO's 16 blur
                                  // the sun's sharp edges as the camera moves: book 11's hard cases)
  int kernel_parts = 8;           // PCSS's disk (32 taps) in parts, a part a frame (4 taps)
  bool turn = true;               // the disk turned by ao_turn(frame) too
  float depth_tolerance = 0.05f;  // the disocclusion test's (TaaSettings' meaning)
  float depth_slope = 1.5f;
};
// [/temporal-shadow-settings]

// Chapter 06's settings for frame i (counted from the history's start): PCSS's part i mod
// kernel_parts of its disk, turned by ao_turn(i), the sun's visibility given by the stage;
// `shadows` unchanged when `temporal` is off (its own taps every frame, looked up in the hook).
ch06::ShadowSettings frame_shadows(const ch06::ShadowSettings& shadows, const TemporalShadowSettings& temporal,
                                   unsigned frame);

class TemporalShadowStage : public ch03::FrameStage {
 public:
  // `shadows`: the frame's shadow stage when before_lights runs (chapter 10's whole frame makes
  // its stages again when its plan changes).
  TemporalShadowStage(std::function<ch06::ShadowStage*()> shadows, const MotionStage& motion);
  void reload_shaders() { visibility_pass_.reset(); accumulate_.reload(); }
  void set(const TemporalShadowSettings& settings) { settings_ = settings; }
  void reset() { reset_ = true; }  // the next frame starts the history again (a camera cut)

  void before_lights(ch03::DeferredFrame& frame, PassMetrics* metrics) override;

  // After render(): R32F, the sun's visibility the lights read (accumulated when enabled); R32F,
  // this frame's PCSS penumbra radius in metres (0 where its search found no blocker); RG32F, x
  // the accumulated visibility, y the frames in it (1: dropped or started this frame).
  GLuint visibility() const { return visibility_.id(); }
  GLuint radius() const { return radius_.id(); }
  GLuint history() const { return history_[cur_].id(); }
  bool ran() const { return ran_; }
  std::size_t allocated_bytes() const { return std::size_t(width_) * height_ * (4 + 4 + 8 * 2); }

 private:
  std::function<ch06::ShadowStage*()> shadows_;
  const MotionStage& motion_;
  std::unique_ptr<ShaderProgram> visibility_pass_;  // compiled with the shadow stage's defines
  std::vector<std::string> visibility_defines_;
  ShaderProgram accumulate_;
  TemporalShadowSettings settings_;
  bool reset_ = true, ran_ = false;
  gl::Texture visibility_{GL_TEXTURE_2D}, radius_{GL_TEXTURE_2D};
  gl::Texture history_[2] = {gl::Texture(GL_TEXTURE_2D), gl::Texture(GL_TEXTURE_2D)};  // sized on first use
  int width_ = 0, height_ = 0, cur_ = 0;
};

}  // namespace lp::ch11
