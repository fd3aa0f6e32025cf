#include "chapters/03_light_volumes/deferred_frame.h"

#include <iostream>

#include "chapters/01_forward/ground_truth.h"
#include "chapters/03_light_volumes/light_radius.h"
#include "common/error.h"

namespace lp::ch03 {

void FrameOutput::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, width, height);
  glEnable(GL_FRAMEBUFFER_SRGB);  // shaders write linear light; an sRGB target encodes it
}

DeferredFrame::DeferredFrame(const SceneGpu& scene, const ch02::Layout& layout, int sphere_subdivisions)
    : scene_(scene), layout_(layout), geometry_(std::make_unique<ch02::GeometryPass>(scene)),
      volumes_(sphere_subdivisions),
      volume_lights_(volumes_, Strategy::Stencil), ambient_(scene.scene().ambient), background_(ch01::kBackground) {}

void DeferredFrame::reload_shaders() {
  geometry_->reload_shaders();
  volumes_.reload_shaders();
}


void DeferredFrame::set_strategy(Strategy strategy) { volume_lights_.set_strategy(strategy); }

void DeferredFrame::set_local_lights(LocalLightPass* pass) { local_ = pass ? pass : &volume_lights_; }

void DeferredFrame::add_stage(FrameStage& stage) {
  const StageNeeds needs = stage.needs();
  if (needs.units < 0 || needs.blocks < 0) throw Error("a frame stage asked for a negative number of slots");
  stage.slots_ = next_slots_;
  next_slots_.first_unit += GLuint(needs.units);
  next_slots_.first_block += GLuint(needs.blocks);
  stages_.push_back(&stage);
}

void DeferredFrame::bind_hooks() const {
  for (const FrameStage* stage : stages_) stage->bind_hook_resources();
}

void DeferredFrame::prepare_stages(const FrameCamera& camera, const FrameOutput& output, PassMetrics* metrics) {
  output_ = output;
  camera_ = camera;
  for (FrameStage* stage : stages_) stage->before_lights(*this, metrics);
}

// Chapter 03's hook files, each replaced by the one stage that names its own.
ShaderHooks DeferredFrame::hooks() const {
  ShaderHooks hooks, chosen = {"", ""};
  for (const FrameStage* stage : stages_) {
    const ShaderHooks h = stage->shader_hooks();
    hooks.defines.insert(hooks.defines.end(), h.defines.begin(), h.defines.end());
    for (auto [mine, theirs, what] : {std::tuple{&chosen.visibility, &h.visibility, "visibility"},
                                      std::tuple{&chosen.ambient, &h.ambient, "ambient"}}) {
      if (theirs->empty()) continue;
      if (!mine->empty() && *mine != *theirs)
        throw Error(std::string("two stages of the frame both supply its ") + what + " hook: " + *mine + " and " + *theirs);
      *mine = *theirs;
    }
  }
  if (!chosen.visibility.empty()) hooks.visibility = chosen.visibility;
  if (!chosen.ambient.empty()) hooks.ambient = chosen.ambient;
  return hooks;
}

void DeferredFrame::resize(int width, int height) {
  if (width <= 0 || height <= 0)
    throw Error("the deferred frame needs at least one pixel (asked for " + std::to_string(width) + "x" +
                std::to_string(height) + ")");
  if (gbuffer_ && gbuffer_->width() == width && gbuffer_->height() == height) return;
  gbuffer_ = std::make_unique<ch02::GBuffer>(width, height, layout_);
  light_ = std::make_unique<LightBuffer>(width, height, ch02::depth_format(layout_.depth));
}

std::size_t DeferredFrame::allocated_bytes() const {
  if (!gbuffer_) return 0;
  return gbuffer_->bytes_per_pixel() * std::size_t(gbuffer_->width()) * std::size_t(gbuffer_->height()) + light_->bytes();
}

void DeferredFrame::copy_depth_to_output() const {
  const int w = output_.width, h = output_.height;
  glBlitNamedFramebuffer(gbuffer_->framebuffer(), output_.framebuffer, 0, 0, w, h, 0, 0, w, h, GL_DEPTH_BUFFER_BIT,
                         GL_NEAREST);
  const GLint zero = 0;
  glClearNamedFramebufferiv(output_.framebuffer, GL_STENCIL, 0, &zero);
  output_.bind();
}

// [frame]
void DeferredFrame::render(const FrameCamera& camera, const FrameOutput& output, PassMetrics* metrics,
                           const FrameSettings& settings) {
  resize(output.width, output.height);
  output_ = output;
  camera_ = camera;
  const bool heat = settings.show == FrameShow::HeatShaded || settings.show == FrameShow::HeatLit;

  // 1. The surfaces: chapter 02's G-buffer, read by every pass after it.
  {
    auto pass = timed(metrics, "geometry: G-buffer (chapter 02)");
    geometry_->draw(*gbuffer_, camera);
  }
  gbuffer_->bind_textures(0);
  view_ = surface_view(*gbuffer_);
  view_.hooks = hooks();

  // 2. What later chapters compute from the surfaces before any light (shadow maps, AO).
  for (FrameStage* stage : stages_) stage->before_lights(*this, metrics);

  // 3. The light buffer: the G-buffer's depth, a zero stencil, then ambient and the
  //    directional lights for every pixel, and each local light where it reaches.
  light_->begin(gbuffer_->framebuffer());
  bind_hooks();  // for the global and local passes: the stages' own passes may have used any unit
  if (!settings.scene_lights || heat) {
    light_->clear();
  } else {
    auto pass = timed(metrics, "global: ambient + directional (chapter 03)");
    volumes_.draw_global(*light_, view_, ambient_, global_);
  }
  if (settings.scene_lights) {
    const LightVolumes::Output out = settings.show == FrameShow::HeatShaded ? LightVolumes::Output::HeatShaded
                                     : settings.show == FrameShow::HeatLit  ? LightVolumes::Output::HeatLit
                                                                            : LightVolumes::Output::Light;
    if (local_->times_own_passes()) {  // chapter 09: its depth bounds, assignment and shading apart
      local_->set_metrics(metrics);
      local_->draw(*light_, view_, out);
    } else {
      auto pass = timed(metrics, "local lights: " + local_->name());
      local_->draw(*light_, view_, out);
    }
  }

  // 4. Light the later chapters add (chapter 04's tubes).
  light_->bind();
  for (FrameStage* stage : stages_) stage->add_light(*this, metrics);

  // 5. The image: F = albedo * L1 + L2 + emissive, or a picture of the light buffer.
  output.bind();
  bool drawn = false;
  for (FrameStage* stage : stages_) drawn = drawn || stage->composite(*this, metrics);
  if (!drawn) {
    auto pass = timed(metrics, "composite: albedo x L1 + L2 + emissive (chapter 03)");
    if (heat) volumes_.draw_heat(*light_, settings.heat_full_scale);
    else if (settings.show == FrameShow::DiffuseLight) volumes_.draw_light_target(light_->diffuse(), 1.f);
    else if (settings.show == FrameShow::SpecularLight) volumes_.draw_light_target(light_->specular(), 4.f);
    else if (global_ == GlobalPass::Compute && output.image) volumes_.composite_compute(*light_, view_, background_, output.image);
    else volumes_.composite(*light_, view_, background_);
  }

  // 6. What is drawn over the image (glass, pictures).
  for (FrameStage* stage : stages_) {
    output.bind();
    stage->after_composite(*this, metrics);
  }
}
// [/frame]

void use_lights(DeferredFrame& frame, const Scene& scene, const std::vector<Light>& lights, bool say_warnings) {
  frame.volumes().set_lights(build_light_set(lights, cut_threshold(1.f, peak_reflectance(scene)), frame.volumes().shapes()));
  if (say_warnings)
    for (const auto& w : frame.volumes().lights().warnings) std::cerr << "warning: " << w << '\n';
}

}  // namespace lp::ch03
