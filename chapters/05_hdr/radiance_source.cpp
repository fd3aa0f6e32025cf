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
  std::vector<float> rgba(std::size_t(image.width) * image.height * 4, 1.f);
  for (int y = 0; y < image.height; ++y)  // OpenGL's first row is the bottom one
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c)
        rgba[(std::size_t(image.height - 1 - y) * image.width + x) * 4 + c] = image.at(x, y, c);
  gl::Texture t = gl::make_texture_2d(format, image.width, image.height);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(t.id(), 0, 0, 0, image.width, image.height, GL_RGBA, GL_FLOAT, rgba.data());
  return t;
}

Scene rescaled_scene(const Scene& scene, float sun, float glow) {
  Scene s = scene;
  for (auto& l : s.lights)
    if (l.type == LightType::Directional) l.intensity *= sun;
  for (auto& m : s.materials) m.emissive *= glow;
  return s;
}

ForwardRadiance::ForwardRadiance(const Scene& scene) : original_(scene) { set_scales(1, 1); }

void ForwardRadiance::set_scales(float sun, float glow) {
  if (sun == sun_ && glow == glow_) return;
  sun_ = sun;
  glow_ = glow;
  if (!scene_) {
    scene_ = std::make_unique<Scene>(rescaled_scene(original_, sun, glow));
    gpu_ = std::make_unique<SceneGpu>(*scene_);
    forward_ = std::make_unique<ch01::ForwardRenderer>(*gpu_);
  } else {
    // The GPU scene reads materials from *scene_ at draw time: rescale them in place.
    for (std::size_t i = 0; i < scene_->materials.size(); ++i)
      scene_->materials[i].emissive = original_.materials[i].emissive * glow;
    for (std::size_t i = 0; i < scene_->lights.size(); ++i)
      scene_->lights[i].intensity = original_.lights[i].intensity * (original_.lights[i].type == LightType::Directional ? sun : 1.f);
  }
  lights_.upload(scene_->lights);
}

void ForwardRadiance::render(const FrameCamera& camera, const RadianceTarget& target) const {
  target.bind();
  glClearColor(ch01::kBackground.r, ch01::kBackground.g, ch01::kBackground.b, 1.f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  forward_->draw(camera, ch01::ForwardMode::PerPixel, lights_);
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

void DeferredRadiance::render(const FrameCamera& camera, const RadianceTarget& target, PassMetrics* metrics) {
  if (lights_changed_) {
    // [sun-scale]
    // The sun's scale, applied where the lights are packed: a copy of the lights, not of the scene.
    std::vector<Light> lights = scene().lights;
    for (Light& l : lights)
      if (l.type == LightType::Directional) l.intensity *= sun_;
    // [/sun-scale]
    ch03::LightSet set = ch03::build_light_set(lights, cut_threshold(), volumes().shapes());
    if (!warned_)  // the same lights every time: say it once
      for (const auto& warning : set.warnings) std::cerr << "warning: " << warning << '\n';
    warned_ = true;
    volumes().set_lights(std::move(set));
    lights_changed_ = false;
  }
  // [deferred-frame]
  // Chapter 03's frame, into our float target instead of the sRGB output.
  frame_->render(camera, {target.framebuffer(), target.width(), target.height()}, metrics);
  // [/deferred-frame]
}

}  // namespace lp::ch05
