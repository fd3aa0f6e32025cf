#include "chapters/08_ssgi/gi_frame.h"

#include "chapters/03_light_volumes/light_radius.h"

namespace lp::ch08 {

GiFrame::GiFrame(const SceneGpu& scene, int width, int height, int guard_band)
    : scene_(scene), width_(width), height_(height), band_{guard_band}, frame_(scene), stage_(scene),
      target_(band_.width(width), band_.height(height)) {
  frame_.volumes().set_lights(ch03::build_light_set(
      scene.scene().lights, ch03::cut_threshold(1.f, ch03::peak_reflectance(scene.scene())), frame_.volumes().shapes()));
  frame_.add_stage(stage_);
  stage_.set_guard_band(band_.pixels);
}

void GiFrame::render(const FrameCamera& camera, PassMetrics* metrics) {
  frame_.render(band_.widen(camera, width_, height_),
                {target_.framebuffer(), band_.width(width_), band_.height(height_)}, metrics);
}

ImageF GiFrame::indirect(const FrameCamera& camera, GiMode mode, const GiSettings& settings) {
  stage_.set(mode, settings, GiShow::Image, scene_.scene().ambient);
  render(camera);
  if (!stage_.ran()) {
    ImageF none = ImageF::blank(width_, height_, 4);
    for (std::size_t i = 3; i < none.data.size(); i += 4) none.data[i] = 1.f;
    return none;
  }
  return band_.crop(stage_.ssgi().read());
}

ImageRGBA8 GiFrame::image(const FrameCamera& camera, GiMode mode, const GiSettings& settings, GiShow show,
                          float ambient_scale, float exposure) {
  const glm::vec3 ambient = scene_.scene().ambient * ambient_scale;
  frame_.set_ambient(ambient);
  stage_.set(mode, settings, show, ambient, exposure);
  render(camera);
  return band_.crop(target_.read());
}

std::string GiFrame::pass_name(GiMode mode, const GiSettings& settings) {
  return "ssgi: " + kModeNames[int(mode)] + " (" + kPatternNames[int(settings.pattern)] + ")";
}

Measurement GiFrame::measure_frame(const FrameCamera& camera, GiMode mode, const GiSettings& settings, int frames) {
  stage_.set(mode, settings, GiShow::Image, scene_.scene().ambient);
  return measure(metrics_, [&] { render(camera, &metrics_); }, {.frames = frames});
}

PassMeasurement GiFrame::time(const FrameCamera& camera, GiMode mode, const GiSettings& settings, int frames) {
  return measure_frame(camera, mode, settings, frames).pass(pass_name(mode, settings));
}

}  // namespace lp::ch08
