#pragma once
// Chapter 10's whole frame over time: each frame's projection jittered (Halton 2, 3), the
// motion vectors drawn after the G-buffer, and TAA after the composite and the glass, before
// chapter 05's HDR chain. The frame remembers the last camera; a cut starts history again.
//
//   TemporalFrame frame(scene_gpu);
//   frame.render(camera, {target, w, h}, settings, dt, cut, &metrics);   // camera without jitter
#include "chapters/10_frame/whole_frame.h"
#include "chapters/11_temporal/jitter.h"
#include "chapters/11_temporal/motion.h"
#include "chapters/11_temporal/taa.h"
#include "chapters/11_temporal/temporal_gi.h"
#include "chapters/11_temporal/temporal_shadows.h"
#include "common/image.h"

namespace lp::ch11 {

// [temporal-settings]
struct TemporalSettings {
  ch10::WholeFrameSettings whole;  // chapter 10's stages
  TaaSettings taa;                 // taa.enabled false: chapter 10's frame, no jitter, no motion
  unsigned jitter_period = 8;      // Halton(2, 3) points before the pattern repeats
  bool jitter_alone = false;       // jitter without TAA too (tests: the frames TAA would blend)
  bool motion_alone = false;       // the motion pass without TAA too (measure.h: disocclusion for every variant)
  TemporalGiSettings gi;           // chapter 08's AO and indirect light accumulated (temporal_gi.h)
  // The sun's shadow soft: chapter 06's PCSS (its 32 taps a frame) instead of chapter 10's PCF
  // 3x3, and with shadows.enabled a part of them a frame, accumulated (temporal_shadows.h).
  bool pcss = false;
  int pcss_taps = 0;  // its disk's taps (0: chapter 06's 32)
  TemporalShadowSettings shadows{.enabled = false};
};
// [/temporal-settings]

class TemporalFrame {
 public:
  explicit TemporalFrame(const SceneGpu& scene);
  void reload_shaders();
  // One frame of a sequence. `camera` without jitter; `cut`: a new shot (no history, the eye
  // adapted at once), as on the first frame.
  void render(const FrameCamera& camera, const ch03::FrameOutput& output, const TemporalSettings& s, float dt, bool cut,
              PassMetrics* metrics = nullptr);
  // One frame alone, its projection moved by `offset` pixels, without history (the frames the
  // supersampled truth averages). The next render() starts a new sequence.
  void render_still(const FrameCamera& camera, glm::vec2 offset, const ch03::FrameOutput& output, const TemporalSettings& s);

  glm::vec2 last_jitter() const { return jitter_; }
  ch10::WholeFrame& whole() { return whole_; }
  const MotionStage& motion() const { return motion_; }
  const TaaStage& taa() const { return taa_; }
  const TemporalGiStage& gi() const { return gi_; }
  const TemporalShadowStage& shadows() const { return shadows_; }
  std::size_t allocated_bytes() const {
    return whole_.allocated_bytes() + motion_.allocated_bytes() + taa_.allocated_bytes() + gi_.allocated_bytes() +
           shadows_.allocated_bytes();
  }

 private:
  ch10::WholeFrame whole_;
  MotionStage motion_;
  TaaStage taa_;
  TemporalGiStage gi_;
  TemporalShadowStage shadows_;
  FrameCamera previous_;
  bool sequence_ = false;
  unsigned index_ = 0, gi_index_ = 0;  // gi_index_: frames since the last new shot
  glm::vec2 jitter_{0};
};

// [truth-grid]
// The supersampled truth of a frame: 16 frames of the whole frame, each moved to one point of
// a 4x4 grid over the pixel (stratified, so every sub-pixel region counts equally), without
// history, averaged in linear light. The same pixel size as the frame, so the screen-space
// stages (AO and indirect light in pixels, bloom) see the scene as the frame does.
ImageF supersampled(TemporalFrame& frame, const FrameCamera& camera, int width, int height, const TemporalSettings& s,
                    int grid = 4);
// [/truth-grid]

// Chapter 06's PCSS for the whole frame's sun (TemporalSettings::pcss): pcss_taps, the frame's cascades.
ch06::ShadowSettings pcss_settings(const TemporalSettings& s);

// The output read back as linear RGB floats (sRGB decoded), rows top to bottom.
ImageF read_linear(GLuint framebuffer, int width, int height);

}  // namespace lp::ch11
