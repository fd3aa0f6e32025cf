#pragma once
// Chapter 07's ambient occlusion as a stage of chapter 03's deferred frame: after the
// G-buffer and before any light, the AO pass (ssao.h) reads the surfaces; its texture goes on
// the one texture unit the frame gives the stage (AO_UNIT to GLSL), where the frame's ambient
// hook, shaders/ao_ambient.glsl, multiplies the ambient light by it. The direct lights are
// untouched.
//
//   ch03::DeferredFrame frame(scene_gpu);  AoStage ao;  frame.add_stage(ao);
//   ao.set({.method = AoMethod::Disk, .samples = 32}, AoShow::Image, scene.ambient);
//   frame.render(camera, output, &metrics);
#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/07_ssao/ssao.h"
#include "common/target.h"

namespace lp::ch07 {

// The lit image; the AO term alone (grey), before the blur; or a picture the program computed
// (the truth, the error) given with set_picture().
enum class AoShow { Image, Ao, Raw, Picture };

class AoStage : public ch03::FrameStage {
 public:
  AoStage();
  void reload_shaders();
  // What to compute and show. `ambient` is the frame's ambient light: where it is zero (and
  // the AO is not shown) AO would change nothing, and no AO pass runs.
  void set(const AoSettings& settings, AoShow show, glm::vec3 ambient);
  // What AoShow::Picture shows: a one-channel image (rows top to bottom), as grey, or as a heat
  // map where `heat_full_scale` is red.
  void set_picture(const ImageF& picture, float heat_full_scale = 0.f);
  bool ran() const { return ran_; }  // whether the last frame ran the AO pass
  const Ssao& ssao() const { return ssao_; }
  const AoSettings& settings() const { return settings_; }

  ch03::StageNeeds needs() const override { return {.units = 1}; }
  ch03::ShaderHooks shader_hooks() const override;
  void bind_hook_resources() const override;
  void before_lights(ch03::DeferredFrame& frame, PassMetrics* metrics) override;
  bool composite(ch03::DeferredFrame& frame, PassMetrics* metrics) override;

 private:
  std::vector<std::string> unit_defines() const;  // {"AO_UNIT <its unit>"}
  Ssao ssao_;
  AoSettings settings_;
  AoShow show_ = AoShow::Image;
  bool needed_ = true, ran_ = false;
  gl::Texture white_;
  PictureTexture picture_{1};  // set_picture()'s, one channel
  float heat_ = 0.f;  // A = 1: what the hook reads when no AO pass runs
  std::unique_ptr<ShaderProgram> show_program_;
  gl::VertexArray vao_;
};

}  // namespace lp::ch07
