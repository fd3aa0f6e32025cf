#pragma once
// Chapter 08's AO and indirect light as one stage of chapter 03's deferred frame. Indirect
// light needs this frame's direct light, so the pass cannot run before the lights (where
// chapter 07's AO runs): it runs in add_light, after every direct light (chapter 03's, and
// chapter 04's tubes when their stage was added first), reading the light buffer's L1. The
// ambient light, which the AO darkens, must then not be in L1 yet (it would bounce too, and
// would be added before the AO exists): the stage's ambient hook, shaders/no_ambient.glsl,
// leaves it out of chapter 03's global pass, and the stage adds A x ambient + L1_ind into
// the light buffer itself. The composite, albedo x L1 + L2 + emissive, then shows both.
//
//   ch03::DeferredFrame frame(scene_gpu);  GiStage gi(scene_gpu);  frame.add_stage(gi);
//   gi.set(GiMode::Ssgi, {.samples = 16}, GiShow::Image, scene.ambient);
//   frame.render(camera, output, &metrics);
#include <memory>

#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/08_ssgi/ssgi.h"
#include "common/target.h"

namespace lp::ch08 {

// ssgi: AO and indirect light; ssao: the AO alone (the narrow disk); off: no pass, the
// constant ambient light (chapter 03's image, summed in another order).
enum class GiMode { Ssgi, Ssao, Off };
inline const std::vector<std::string> kModeNames = {"ssgi", "ssao", "off"};

// The lit image; the indirect light the pixels reflect (albedo x L1_ind); the AO term; an RGB
// picture the program computed (the truth); a one-channel picture as a heat map (the error);
// the back-face layer: the light its surfaces send, albedo x L1 (black where there is none).
enum class GiShow { Image, Indirect, Ao, Picture, Heat, BackFaces };

// What may change the pass's result before it is added to the light buffer (chapter 11
// accumulates it over frames): called in add_light after each compute, on the texture that
// Ssgi::texture() names, which it may overwrite.
class GiFilter {
 public:
  virtual ~GiFilter() = default;
  virtual void filter(ch03::DeferredFrame& frame, const Ssgi& ssgi, PassMetrics* metrics) = 0;
};

class GiStage : public ch03::FrameStage {
 public:
  explicit GiStage(const SceneGpu& scene) : scene_(scene) {}
  void reload_shaders();
  void set(GiMode mode, const GiSettings& settings, GiShow show, glm::vec3 ambient, float exposure = 1.f);
  // What Picture shows (rgb, rows top to bottom: L1_ind, multiplied by the albedo as Indirect
  // is) and what Heat shows (one channel, red at heat_full_scale).
  void set_picture(const ImageF& picture, float heat_full_scale = 0.f);
  // The frame is drawn `pixels` wider on every side than the screen (guard_band.h): the wide
  // disk's screen clamp stays a fraction of the screen's height, and the pictures (truth,
  // error: screen-sized) are drawn into the screen's part.
  void set_guard_band(int pixels) { guard_ = pixels; }
  int guard_band() const { return guard_; }
  const BackFaceLayer& back_faces() const { return back_; }
  bool drew_back_faces() const { return drew_back_; }
  void set_filter(GiFilter* filter) { filter_ = filter; }  // nullptr: none
  bool ran() const { return ran_; }
  const Ssgi& ssgi() const { return ssgi_; }
  const GiSettings& settings() const { return settings_; }
  GiMode mode() const { return mode_; }

  // Three units for its own passes (GI_UNIT to GLSL: the indirect light, the back faces'
  // albedo and light); its ambient hook reads none.
  ch03::StageNeeds needs() const override { return {.units = 3}; }
  ch03::ShaderHooks shader_hooks() const override { return {"", "08_ssgi/shaders/no_ambient.glsl"}; }
  // Adds A x ambient + L1_ind into the light buffer: as a fragment pass, or in compute where the
  // frame runs its global pass in compute (DeferredFrame::global_pass): the same sum.
  void add_light(ch03::DeferredFrame& frame, PassMetrics* metrics) override;
  bool composite(ch03::DeferredFrame& frame, PassMetrics* metrics) override;

 private:
  std::vector<std::string> unit_defines() const;  // {"GI_UNIT <its first unit>"}
  const SceneGpu& scene_;
  Ssgi ssgi_;
  BackFaceLayer back_;
  bool drew_back_ = false;
  int guard_ = 0;
  GiSettings settings_;
  GiMode mode_ = GiMode::Ssgi;
  GiShow show_ = GiShow::Image;
  glm::vec3 ambient_{0};
  float exposure_ = 1.f, heat_ = 0.f;
  bool ran_ = false;
  GiFilter* filter_ = nullptr;
  PictureTexture picture_{4};  // set_picture()'s, rgb
  std::unique_ptr<ShaderProgram> add_program_, add_compute_, show_program_;
  gl::VertexArray vao_;
};

}  // namespace lp::ch08
