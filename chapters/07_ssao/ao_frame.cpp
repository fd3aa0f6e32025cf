#include "chapters/07_ssao/ao_frame.h"

namespace lp::ch07 {

AoFrame::AoFrame(const SceneGpu& scene, int width, int height)
    : scene_(scene), width_(width), height_(height), frame_(scene), target_(width, height) {
  frame_.add_stage(stage_);
}

ImageF AoFrame::ao(const FrameCamera& camera, const AoSettings& settings) {
  stage_.set(settings, AoShow::Ao, scene_.scene().ambient);
  frame_.render(camera, {target_.framebuffer(), width_, height_});
  if (!stage_.ran()) {
    ImageF one = ImageF::blank(width_, height_, 1);
    for (float& v : one.data) v = 1.f;
    return one;
  }
  return stage_.ssao().read_full(width_, height_);
}

ImageRGBA8 AoFrame::image(const FrameCamera& camera, const AoSettings& settings, AoShow show, float ambient_scale) {
  const glm::vec3 ambient = scene_.scene().ambient * ambient_scale;
  frame_.set_ambient(ambient);
  stage_.set(settings, show, ambient);
  frame_.render(camera, {target_.framebuffer(), width_, height_});
  return target_.read();
}

PassMeasurement AoFrame::time(const FrameCamera& camera, const AoSettings& settings, int frames) {
  stage_.set(settings, AoShow::Ao, scene_.scene().ambient);
  Measurement m = measure(metrics_, [&] { frame_.render(camera, {target_.framebuffer(), width_, height_}, &metrics_); },
                          {.frames = frames});
  return m.pass("ssao: " + kMethodNames[int(settings.method)]);
}

}  // namespace lp::ch07
