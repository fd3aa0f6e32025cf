#pragma once
// Chapter 08's AO and indirect light accumulated over frames, as temporal_ao.h does chapter 07's
// AO: each frame the pass reads few samples (the next part of a larger pattern, the randomised
// pattern turned by the frame's angle), and a compute pass blends its result into the last
// frames' moved by the motion vectors, dropping the history where the surface was hidden last
// frame (shaders/disocclusion.glsl). Not a stage of its own: a filter of chapter 08's stage
// (GiStage::set_filter), run after its pass and before the light buffer adds the result, so the
// frame's lighting uses the accumulated AO and indirect light. Chapter 10's whole frame takes
// it through WholeFrame::set_gi_filter; TemporalFrame does that (TemporalSettings::gi).
//
//   TemporalGiStage temporal(motion);  gi_stage.set_filter(&temporal);  temporal.set(settings);
//   gi_stage.set(..., frame_gi(gi_settings, settings, i), ...);  if (cut) temporal.reset();
#include "chapters/08_ssgi/gi_stage.h"
#include "chapters/11_temporal/motion.h"

namespace lp::ch11 {

// [temporal-gi-settings]
struct TemporalGiSettings {
  bool enabled = false;           // off: chapter 08's pass of this frame alone, with its own samples
  int samples = 4;                // chapter 08's samples a frame (its pattern: samples x kernel_parts points)
  int max_frames = 16;            // this frame weighs at least 1 / max_frames
  int kernel_parts = 8;           // a part of the pattern a frame
  bool turn = true;               // the randomised pattern turned by ao_turn(frame) too
  float depth_tolerance = 0.05f;  // the disocclusion test's (TaaSettings' meaning)
  float depth_slope = 1.5f;
};
// [/temporal-gi-settings]

// Chapter 08's settings for frame i (counted from the history's start): `samples` of them, the
// pattern's part i mod kernel_parts, turned by ao_turn(i); `gi` unchanged when `temporal` is off.
ch08::GiSettings frame_gi(const ch08::GiSettings& gi, const TemporalGiSettings& temporal, unsigned frame);

class TemporalGiStage : public ch08::GiFilter {
 public:
  explicit TemporalGiStage(const MotionStage& motion);
  void reload_shaders() { accumulate_.reload(); }
  void set(const TemporalGiSettings& settings) { settings_ = settings; }
  const TemporalGiSettings& settings() const { return settings_; }
  void reset() { reset_ = true; }  // the next frame starts the history again (a camera cut)

  void filter(ch03::DeferredFrame& frame, const ch08::Ssgi& ssgi, PassMetrics* metrics) override;

  // After the pass: RGBA32F, rgb L1_ind before the clamp and a A accumulated; RG32F, r the frames
  // in each pixel's history (1: dropped or started this frame), g the transfer total accumulated
  // (the clamp's denominator); whether this frame ran.
  GLuint history() const { return history_[cur_].id(); }
  GLuint frames() const { return frames_[cur_].id(); }
  bool ran() const { return ran_; }
  std::size_t allocated_bytes() const { return std::size_t(width_) * height_ * (16 + 8) * 2; }

 private:
  const MotionStage& motion_;
  ShaderProgram accumulate_;
  TemporalGiSettings settings_;
  bool reset_ = true, ran_ = false;
  gl::Texture history_[2] = {gl::Texture(GL_TEXTURE_2D), gl::Texture(GL_TEXTURE_2D)};  // sized on first use
  gl::Texture frames_[2] = {gl::Texture(GL_TEXTURE_2D), gl::Texture(GL_TEXTURE_2D)};
  int width_ = 0, height_ = 0, cur_ = 0;
};

}  // namespace lp::ch11
