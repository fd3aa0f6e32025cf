#include "chapters/08_ssgi/gi_frame.h"

#include "chapters/03_light_volumes/light_radius.h"

namespace lp::ch08 {

GiFrame::GiFrame(const SceneGpu& scene, int width, int height)
    : scene_(scene), width_(width), height_(height), frame_(scene), target_(width, height) {
  frame_.volumes().set_lights(ch03::build_light_set(
      scene.scene().lights, ch03::cut_threshold(1.f, ch03::peak_reflectance(scene.scene())), frame_.volumes().shapes()));
  frame_.add_stage(stage_);
}

ImageF GiFrame::indirect(const FrameCamera& camera, GiMode mode, const GiSettings& settings) {
  stage_.set(mode, settings, GiShow::Image, scene_.scene().ambient);
  frame_.render(camera, {target_.framebuffer(), width_, height_});
  if (!stage_.ran()) {
    ImageF none = ImageF::blank(width_, height_, 4);
    for (std::size_t i = 3; i < none.data.size(); i += 4) none.data[i] = 1.f;
    return none;
  }
  return stage_.ssgi().read();
}

ImageRGBA8 GiFrame::image(const FrameCamera& camera, GiMode mode, const GiSettings& settings, GiShow show,
                          float ambient_scale, float exposure) {
  const glm::vec3 ambient = scene_.scene().ambient * ambient_scale;
  frame_.set_ambient(ambient);
  stage_.set(mode, settings, show, ambient, exposure);
  frame_.render(camera, {target_.framebuffer(), width_, height_});
  return target_.read();
}

PassMeasurement GiFrame::time(const FrameCamera& camera, GiMode mode, const GiSettings& settings, int frames) {
  stage_.set(mode, settings, GiShow::Image, scene_.scene().ambient);
  Measurement m = measure(metrics_, [&] { frame_.render(camera, {target_.framebuffer(), width_, height_}, &metrics_); },
                          {.frames = frames});
  return m.pass("ssgi: " + kModeNames[int(mode)] + " (" + kPatternNames[int(settings.pattern)] + ")");
}

}  // namespace lp::ch08
