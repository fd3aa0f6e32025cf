#include "chapters/05_hdr/radiance_source.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>
#include <string>

#include "chapters/01_forward/ground_truth.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "common/error.h"

namespace lp::ch05 {

gl::Texture upload_radiance(const ImageF& image, GLenum format) {
  if (image.channels < 3) throw Error("upload_radiance needs an RGB or RGBA image");
  return upload_picture(image, format);
}

// [sun-scale]
std::vector<Light> sun_scaled(const std::vector<Light>& lights, float sun) {
  std::vector<Light> out = lights;
  for (Light& l : out)
    if (l.type == LightType::Directional) l.intensity *= sun;
  return out;
}
// [/sun-scale]

Scene rescaled_scene(const Scene& scene, float sun, float glow) {
  Scene s = scene;
  s.lights = sun_scaled(s.lights, sun);
  for (auto& m : s.materials) m.emissive *= glow;
  return s;
}

ForwardRadiance::ForwardRadiance(const SceneGpu& scene) : gpu_(scene), forward_(gpu_) { set_scales(1, 1); }

ForwardRadiance::ForwardRadiance(const Scene& scene)
    : owned_(std::make_unique<SceneGpu>(scene)), gpu_(*owned_), forward_(gpu_) {
  set_scales(1, 1);
}

void ForwardRadiance::set_scales(float sun, float glow) {
  if (sun == sun_ && glow == glow_) return;
  if (sun != sun_) lights_.upload(sun_scaled(gpu_.scene().lights, sun));
  forward_.set_emissive_scale(glow);
  sun_ = sun;
  glow_ = glow;
}

void ForwardRadiance::render(const FrameCamera& camera, const RadianceTarget& target) const {
  target.bind();
  glClearColor(ch01::kBackground.r, ch01::kBackground.g, ch01::kBackground.b, 1.f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  forward_.draw(camera, ch01::ForwardMode::PerPixel, lights_);
}

// --- Chapter 03's deferred path ----------------------------------------------------------------

DeferredRadiance::DeferredRadiance(const SceneGpu& scene, const ch02::Layout& layout, ch03::Strategy strategy)
    : gpu_(scene), frame_(std::make_unique<ch03::DeferredFrame>(gpu_, layout)),
      peak_reflectance_(ch03::peak_reflectance(scene.scene())), sun_(1), glow_(1) {
  frame_->set_strategy(strategy);
}

DeferredRadiance::DeferredRadiance(const Scene& scene, const ch02::Layout& layout, ch03::Strategy strategy)
    : owned_(std::make_unique<SceneGpu>(scene)), gpu_(*owned_), frame_(std::make_unique<ch03::DeferredFrame>(gpu_, layout)),
      peak_reflectance_(ch03::peak_reflectance(scene)), sun_(1), glow_(1) {
  frame_->set_strategy(strategy);
}

void DeferredRadiance::set_scales(float sun, float glow) {
  if (sun == sun_ && glow == glow_) return;
  frame_->set_emissive_scale(glow);
  if (sun != sun_) lights_changed_ = true;
  sun_ = sun;
  glow_ = glow;
}

void DeferredRadiance::set_cut_exposure(float exposure) {
  if (!(exposure > 0.f) || !std::isfinite(exposure)) throw Error("the light cut needs a positive, finite exposure");
  // [quarter-stop]
  const float rounded = std::exp2(std::ceil(std::log2(exposure) * 4.f) / 4.f);
  // [/quarter-stop]
  if (rounded != cut_exposure_) lights_changed_ = true;
  cut_exposure_ = rounded;
}

float DeferredRadiance::cut_threshold() const { return ch03::cut_threshold(cut_exposure_, peak_reflectance_); }

void DeferredRadiance::update_lights() {
  if (lights_changed_) {
    // The sun's scale, applied where the lights are packed: a copy of the lights, not of the scene.
    ch03::LightSet set = ch03::build_light_set(sun_scaled(scene().lights, sun_), cut_threshold(), volumes().shapes());
    if (!warned_)  // the same lights every time: say it once
      for (const auto& warning : set.warnings) std::cerr << "warning: " << warning << '\n';
    warned_ = true;
    volumes().set_lights(std::move(set));
    lights_changed_ = false;
  }
}

void DeferredRadiance::render(const FrameCamera& camera, const RadianceTarget& target, PassMetrics* metrics) {
  update_lights();
  // [deferred-frame]
  // Chapter 03's frame, into our float target instead of the sRGB output.
  // (Its colour as an image where it is RGBA16F: the composite may run in compute.)
  const GLuint image = target.format() == GL_RGBA16F ? target.texture() : 0;
  frame_->render(camera, {target.framebuffer(), target.width(), target.height(), image}, metrics);
  // [/deferred-frame]
}

}  // namespace lp::ch05
