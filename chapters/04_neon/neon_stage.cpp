#include "chapters/04_neon/neon_stage.h"

namespace lp::ch04 {

NeonStage::NeonStage(const SceneGpu& scene, const NeonTubes& tubes) : tubes_(tubes), glass_(scene) {}

void NeonStage::reload_shaders() {
  volumes_.reload_shaders();
  glass_.reload_shaders();
}

void NeonStage::set(const NeonDraw& how, NeonPicture picture) {
  how_ = how;
  picture_ = picture;
}

// [neon-stage]
void NeonStage::add_light(ch03::DeferredFrame& frame, PassMetrics* metrics) {
  if (!light_by_volumes_) return;
  auto pass = timed(metrics, "neon: capsule volumes, stencil");
  volumes_.draw(tubes_, frame.light(), frame.view(), how_, picture_ == NeonPicture::Waste);
}

bool NeonStage::composite(ch03::DeferredFrame& frame, PassMetrics* metrics) {
  if (wants_scene_lights()) return false;  // chapter 03's composite, with the tubes' light in it
  auto pass = timed(metrics, "composite: the tubes' light alone");
  if (picture_ == NeonPicture::Waste) frame.volumes().draw_light_target(frame.light().diffuse(), 1.f);
  else volumes_.draw_term(frame.light(), frame.view(), how_.term, frame.background());
  return true;
}

void NeonStage::after_composite(ch03::DeferredFrame& frame, PassMetrics* metrics) {
  const bool pictures = picture_ == NeonPicture::Capsules || picture_ == NeonPicture::Masks;
  if (!pictures && !wants_scene_lights()) return;
  frame.copy_depth_to_output();  // the glass and the pictures are depth-tested against the scene
  if (pictures) volumes_.draw_pictures(tubes_, frame.view(), picture_ == NeonPicture::Masks);
  if (wants_scene_lights()) draw_glass(frame.camera(), metrics);
}

void NeonStage::draw_glass(const FrameCamera& camera, PassMetrics* metrics) const {
  auto pass = timed(metrics, "glass: the tubes themselves");
  glass_.draw_glass(camera, tubes_);
}
// [/neon-stage]

}  // namespace lp::ch04
