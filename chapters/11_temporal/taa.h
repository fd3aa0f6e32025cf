#pragma once
// Temporal anti-aliasing as a stage of chapter 03's frame, after the composite (and after
// chapter 10's glass): this frame's jittered radiance blended into the history, the last
// frames' result moved by the motion vectors (motion.h). The result replaces the frame's
// float radiance, so chapter 05's HDR chain tonemaps the anti-aliased image.
//
//   TaaStage taa(motion);
//   frame.add_stage(motion); frame.add_stage(taa);   // the glass's stage between them
//   taa.set(settings, exposure); if (cut) taa.reset();
#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/11_temporal/motion.h"
#include "common/gl.h"
#include "common/shader.h"

namespace lp::ch11 {

enum class HistoryFilter { Bilinear, CatmullRom };
enum class HistoryClip { Off, ClampRgb, ClipYCoCg };

// [taa-settings]
struct TaaSettings {
  bool enabled = true;                               // off: the frame as chapter 10 draws it
  float alpha = 0.1f;                                // this frame's weight in the blend
  HistoryFilter filter = HistoryFilter::CatmullRom;  // how the history is read between its texels
  HistoryClip clip = HistoryClip::ClipYCoCg;         // the history held to this frame's 3x3 neighbourhood
  bool reject_disocclusion = true;                   // history dropped where the surface was hidden
  float depth_tolerance = 0.05f;                     // relative: a depth this far from the last frame's is another surface
  float depth_slope = 1.5f;                          // pixels: plus the depth's change along the surface over this many
  bool tonemapped = true;                            // blend in a tonemapped space (weights 1 / (1 + exposed luminance))
  bool unjitter = true;                              // this frame's pixel rebuilt at its centre from the 3x3's jittered samples
  float gamma = 1.f;                                 // > 0: variance clip, the box mean +- gamma sigma; 0: the extremes
  float alpha_moving = 0.5f;                         // this frame's weight where the surface moves a pixel a frame or more
  int box_memory = 8;                                // frames: a still surface's box keeps the last frames' (1 - 1/N a frame); 0: this frame's alone
};
// [/taa-settings]

class TaaStage : public ch03::FrameStage {
 public:
  explicit TaaStage(const MotionStage& motion);
  void reload_shaders() { resolve_.reload(); }
  // `exposure_state`: chapter 05's eye (ExposureState), whose exposure the tonemapped blend
  // uses: the last frame's, read on the GPU (0: none yet, the blend uses 1).
  void set(const TaaSettings& settings, GLuint exposure_state) {
    settings_ = settings;
    exposure_state_ = exposure_state;
  }
  void set_jitter(glm::vec2 offset) { jitter_ = offset; }  // this frame's, in pixels
  void reset() { reset_ = true; }  // the next frame starts the history again (a camera cut)

  void after_composite(ch03::DeferredFrame& frame, PassMetrics* metrics) override;

  // After render(): the resolved radiance (RGBA16F), where its history was dropped (R8: 1) and
  // the remembered box's corners (RGBA16F, the clip's space).
  GLuint history() const { return history_[cur_].id(); }
  GLuint rejected() const { return rejected_.id(); }
  GLuint box_lo() const { return box_lo_[cur_].id(); }
  GLuint box_hi() const { return box_hi_[cur_].id(); }
  std::size_t allocated_bytes() const { return std::size_t(width_) * height_ * (8 * 2 + 8 * 4 + 1); }

 private:
  void resize(int width, int height);
  const MotionStage& motion_;
  ShaderProgram resolve_;
  TaaSettings settings_;
  GLuint exposure_state_ = 0;
  glm::vec2 jitter_{0};
  bool reset_ = true;
  gl::Texture history_[2] = {gl::Texture(GL_TEXTURE_2D), gl::Texture(GL_TEXTURE_2D)}, rejected_{GL_TEXTURE_2D};  // sized by resize()
  gl::Texture box_lo_[2] = {gl::Texture(GL_TEXTURE_2D), gl::Texture(GL_TEXTURE_2D)};
  gl::Texture box_hi_[2] = {gl::Texture(GL_TEXTURE_2D), gl::Texture(GL_TEXTURE_2D)};
  gl::Framebuffer fbo_[2];
  gl::Sampler bilinear_;
  gl::VertexArray empty_;
  int width_ = 0, height_ = 0, cur_ = 0;
};

}  // namespace lp::ch11
