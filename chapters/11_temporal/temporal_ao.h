#pragma once
// Chapter 07's AO accumulated over frames. Each frame's estimate is cheap (few samples: the next
// part of a larger kernel, the noise tile turned by the frame's angle, so successive frames look
// in other directions), and
// a compute pass blends it into the last frames' result moved by the motion vectors (motion.h),
// dropping the history where the surface was hidden last frame (the test TAA's resolve uses,
// shaders/disocclusion.glsl). A stage of chapter 03's frame after chapter 07's AoStage and the
// MotionStage: the result replaces the AO texture the ambient hook reads, as TAA's replaces
// the radiance.
//
//   frame.add_stage(ao); frame.add_stage(motion); frame.add_stage(temporal);
//   ao.set(frame_ao(ao_settings, temporal_settings, i), ...); temporal.set(temporal_settings);
//   if (cut) temporal.reset();
#include "chapters/07_ssao/ao_stage.h"
#include "chapters/11_temporal/motion.h"

namespace lp::ch11 {

// [temporal-ao-settings]
struct TemporalAoSettings {
  bool enabled = true;            // off: chapter 07's AO of this frame alone
  int max_frames = 16;            // this frame weighs at least 1 / max_frames (the history's reach)
  int kernel_parts = 8;           // chapter 07's classic kernel of samples x parts points, a part a frame
  bool turn = true;               // the noise tile turned by ao_turn(frame) too
  float depth_tolerance = 0.05f;  // the disocclusion test's (TaaSettings' meaning)
  float depth_slope = 1.5f;
};
// [/temporal-ao-settings]

// Frame i's turn of chapter 07's noise tile (AoSettings::turn): the golden angle times i, so any
// run of frames spreads its turns evenly around the circle.
float ao_turn(unsigned frame);
// Chapter 07's settings for frame i (counted from the history's start): the kernel's part i
// mod kernel_parts, turned by ao_turn(i); `ao` unchanged when `temporal` is off.
ch07::AoSettings frame_ao(const ch07::AoSettings& ao, const TemporalAoSettings& temporal, unsigned frame);

// What an accumulation pass (ao_accumulate.comp, gi_accumulate.comp) reads besides its own
// images: its settings, `history` on unit 1, this frame's motion on unit 2 and the last frame's
// on unit 3 (this frame's again on a reset, when the history is not read). Leaves `p` in use.
void use_accumulation(ShaderProgram& p, const MotionStage& motion, bool reset, int max_frames, float depth_tolerance,
                      float depth_slope, GLuint history);

class TemporalAoStage : public ch03::FrameStage {
 public:
  TemporalAoStage(const ch07::AoStage& ao, const MotionStage& motion);
  void reload_shaders() { accumulate_.reload(); }
  void set(const TemporalAoSettings& settings) { settings_ = settings; }
  void reset() { reset_ = true; }  // the next frame starts the history again (a camera cut)

  void before_lights(ch03::DeferredFrame& frame, PassMetrics* metrics) override;

  // After render(): RG32F, x the accumulated AO, y the frames in it (1: dropped this frame).
  GLuint history() const { return history_[cur_].id(); }
  std::size_t allocated_bytes() const { return std::size_t(width_) * height_ * 8 * 2; }

 private:
  const ch07::AoStage& ao_;
  const MotionStage& motion_;
  ShaderProgram accumulate_;
  TemporalAoSettings settings_;
  bool reset_ = true;
  gl::Texture history_[2] = {gl::Texture(GL_TEXTURE_2D), gl::Texture(GL_TEXTURE_2D)};  // sized on first use
  int width_ = 0, height_ = 0, cur_ = 0;
};

}  // namespace lp::ch11
