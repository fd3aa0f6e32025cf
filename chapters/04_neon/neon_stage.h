#pragma once
// Chapter 04's tubes as a stage of chapter 03's deferred frame (deferred_frame.h): after
// chapter 03's lights, each tube's capsule adds its light into the light buffer through
// chapter 03's stencil; chapter 03's composite then makes the image, and the glass of the
// tubes is drawn over it. The program, its tests and chapter 05's HDR frame add this stage to
// the same frame object.
//
//   ch03::DeferredFrame frame(scene_gpu);   NeonStage neon(scene_gpu, tubes);
//   frame.add_stage(neon);
//   neon.set({.method = Method::Improved});
//   frame.render(camera, output, &metrics, {.scene_lights = neon.wants_scene_lights()});
#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/04_neon/neon_forward.h"
#include "chapters/04_neon/neon_volumes.h"

namespace lp::ch04 {

// What the stage draws besides the tubes' light.
enum class NeonPicture {
  None,
  Capsules,  // every capsule as a wireframe over the image
  Masks,     // and each tube's stencil mask, tinted
  Waste,     // instead of the image: what the capsules shade (lit, unlit, kept dark by barn doors)
};

class NeonStage : public ch03::FrameStage {
 public:
  NeonStage(const SceneGpu& scene, const NeonTubes& tubes);
  void reload_shaders();

  void set(const NeonDraw& how, NeonPicture picture = NeonPicture::None);
  // The tubes' diffuse or specular term alone, or the waste picture: the light buffer must
  // hold the tubes' light only (FrameSettings::scene_lights = false).
  bool wants_scene_lights() const { return how_.term == Term::All && picture_ != NeonPicture::Waste; }
  NeonVolumes& volumes() { return volumes_; }  // counting, counts
  const NeonDraw& how() const { return how_; }
  // Off: another pass adds the tubes' light (chapter 09's clusters, ClusteredLights::set_tubes);
  // this stage then draws only the glass of the tubes.
  void set_light_by_volumes(bool on) { light_by_volumes_ = on; }
  const NeonTubes& tubes() const { return tubes_; }

  void add_light(ch03::DeferredFrame& frame, PassMetrics* metrics) override;
  bool composite(ch03::DeferredFrame& frame, PassMetrics* metrics) override;
  void after_composite(ch03::DeferredFrame& frame, PassMetrics* metrics) override;
  // The glass of the tubes alone into the bound target, depth-tested against its depth
  // (after_composite's; chapter 10's MSAA into its samples).
  void draw_glass(const FrameCamera& camera, PassMetrics* metrics) const;

 private:
  const NeonTubes& tubes_;
  NeonVolumes volumes_;
  NeonForward glass_;  // the tubes themselves, drawn forward over the image
  NeonDraw how_;
  NeonPicture picture_ = NeonPicture::None;
  bool light_by_volumes_ = true;
};

}  // namespace lp::ch04
