#include "chapters/07_ssao/ao_stage.h"

namespace lp::ch07 {

AoStage::AoStage() : white_(gl::make_texture_2d(GL_R32F, 1, 1)) {
  const float one = 1.f;
  glTextureSubImage2D(white_.id(), 0, 0, 0, 1, 1, GL_RED, GL_FLOAT, &one);
}

void AoStage::reload_shaders() {
  ssao_.reload_shaders();
  show_program_.reset();
}

void AoStage::set(const AoSettings& settings, AoShow show, glm::vec3 ambient) {
  settings_ = settings;
  show_ = show;
  needed_ = settings.method != AoMethod::Off && (show != AoShow::Image || glm::dot(ambient, ambient) > 0.f);
}

void AoStage::set_picture(const ImageF& picture, float heat_full_scale) {
  picture_.upload(picture);
  heat_ = heat_full_scale;
}

std::vector<std::string> AoStage::unit_defines() const { return {"AO_UNIT " + std::to_string(slots().unit(0))}; }

ch03::ShaderHooks AoStage::shader_hooks() const { return {"", "07_ssao/shaders/ao_ambient.glsl", unit_defines()}; }

// [ao-stage]
void AoStage::before_lights(ch03::DeferredFrame& frame, PassMetrics* metrics) {
  ran_ = needed_;
  if (!ran_) return;
  auto pass = timed(metrics, "ssao: " + kMethodNames[int(settings_.method)]);
  ssao_.compute(frame.gbuffer(), frame.camera(), settings_);
}

// What ao_ambient.glsl reads: this frame's AO, or A = 1 when no pass ran.
void AoStage::bind_hook_resources() const { glBindTextureUnit(slots().unit(0), ran_ ? ssao_.texture() : white_.id()); }

bool AoStage::composite(ch03::DeferredFrame& frame, PassMetrics* metrics) {
  if (show_ == AoShow::Image) return false;  // chapter 03's composite, its ambient darkened by the hook
  auto pass = timed(metrics, "composite: the AO term");
  if (!show_program_)
    show_program_ = std::make_unique<ShaderProgram>(std::vector<ShaderStage>{
        {GL_VERTEX_SHADER, "02_gbuffer/shaders/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "07_ssao/shaders/show_ao.frag"}},
        unit_defines());
  show_program_->use();
  show_program_->set("u_size", glm::vec2(frame.output().width, frame.output().height));
  show_program_->set("u_heat", show_ == AoShow::Picture ? heat_ : 0.f);
  bind_hook_resources();
  if (show_ == AoShow::Raw) glBindTextureUnit(slots().unit(0), ran_ ? ssao_.raw_texture() : white_.id());
  if (show_ == AoShow::Picture) glBindTextureUnit(slots().unit(0), picture_.id());
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glBindVertexArray(vao_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  return true;
}
// [/ao-stage]

}  // namespace lp::ch07
