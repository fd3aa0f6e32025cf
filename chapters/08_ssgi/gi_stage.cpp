#include "chapters/08_ssgi/gi_stage.h"

namespace lp::ch08 {

void GiStage::reload_shaders() {
  ssgi_.reload_shaders();
  back_.reload_shaders();
  add_program_.reset();
  add_compute_.reset();
  show_program_.reset();
}

void GiStage::set(GiMode mode, const GiSettings& settings, GiShow show, glm::vec3 ambient, float exposure) {
  mode_ = mode;
  settings_ = settings;
  settings_.indirect = settings.indirect && mode == GiMode::Ssgi;
  settings_.ao = settings.ao && mode != GiMode::Off;
  show_ = show;
  ambient_ = ambient;
  exposure_ = exposure;
}

void GiStage::set_picture(const ImageF& picture, float heat_full_scale) {
  picture_.upload(picture);
  heat_ = heat_full_scale;
}

std::vector<std::string> GiStage::unit_defines() const { return {"GI_UNIT " + std::to_string(slots().unit(0))}; }

// [gi-stage]
void GiStage::add_light(ch03::DeferredFrame& frame, PassMetrics* metrics) {
  ran_ = mode_ != GiMode::Off;
  const bool back_faces = ran_ && settings_.indirect && settings_.back_faces && settings_.gather == Gather::Disk;
  drew_back_ = back_faces || show_ == GiShow::BackFaces;
  if (drew_back_ && !back_faces) {
    auto pass = timed(metrics, "back-face layer (its picture)");
    back_.draw(scene_, frame);
  }
  if (ran_) {
    // the back-face layer, when asked for, is part of the pass's cost: timed with it
    auto pass = timed(metrics, "ssgi: " + kModeNames[int(mode_)] + " (" + kPatternNames[int(settings_.pattern)] + ")");
    if (back_faces) back_.draw(scene_, frame);
    const BackFaceTextures layer = back_.textures();
    // with a guard band the G-buffer is taller than the screen: the clamp stays the screen's
    GiSettings s = settings_;
    const int h = frame.gbuffer().height();
    if (guard_ > 0 && h > 2 * guard_) s.max_screen_radius *= float(h - 2 * guard_) / float(h);
    ssgi_.compute(frame.gbuffer(), frame.light().diffuse(), frame.camera(), s, back_faces ? &layer : nullptr);
  }
  if (ran_ && filter_) filter_->filter(frame, ssgi_, metrics);
  // A x ambient + L1_ind into the light buffer (bound by the frame), added to the direct light
  auto pass = timed(metrics, "ssgi: add to the light buffer");
  frame.light().bind();
  glViewport(0, 0, frame.light().width(), frame.light().height());
  glBindTextureUnit(slots().unit(0), ran_ ? ssgi_.texture() : 0);
  // With the frame's global pass in compute (chapter 10's), the same sum read and written as an
  // image, one invocation per pixel; else the chapter's fragment pass, blended one plus one.
  if (frame.global_pass() == ch03::GlobalPass::Compute) {
    if (!add_compute_) {
      std::vector<std::string> defines = unit_defines();
      for (const std::string& d : ch03::LightBuffer::image_defines()) defines.push_back(d);
      add_compute_ = std::make_unique<ShaderProgram>(
          std::vector<ShaderStage>{{GL_COMPUTE_SHADER, "08_ssgi/shaders/add_indirect.comp"}}, defines);
    }
    add_compute_->use();
    add_compute_->set("u_ambient", ambient_);
    add_compute_->set("u_gi_on", ran_ ? 1 : 0);
    frame.light().bind_images(GL_READ_WRITE);
    frame.light().dispatch_per_pixel();
    return;
  }
  if (!add_program_)
    add_program_ = std::make_unique<ShaderProgram>(std::vector<ShaderStage>{
        {GL_VERTEX_SHADER, "02_gbuffer/shaders/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "08_ssgi/shaders/add_indirect.frag"}},
        unit_defines());
  add_program_->use();
  add_program_->set("u_ambient", ambient_);
  add_program_->set("u_gi_on", ran_ ? 1 : 0);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glBlendEquation(GL_FUNC_ADD);
  glBindVertexArray(vao_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDisable(GL_BLEND);
}
// [/gi-stage]

bool GiStage::composite(ch03::DeferredFrame& frame, PassMetrics* metrics) {
  if (show_ == GiShow::Image) return false;  // chapter 03's composite shows the light buffer
  auto pass = timed(metrics, "composite: the indirect light");
  if (!show_program_) {
    std::vector<std::string> defines = frame.gbuffer().shader_defines(0);
    for (const std::string& d : unit_defines()) defines.push_back(d);
    show_program_ = std::make_unique<ShaderProgram>(
        std::vector<ShaderStage>{{GL_VERTEX_SHADER, "02_gbuffer/shaders/fullscreen.vert"},
                                 {GL_FRAGMENT_SHADER, "08_ssgi/shaders/show_gi.frag"}},
        defines);
  }
  show_program_->use();
  const int mode = show_ == GiShow::Indirect  ? 0
                 : show_ == GiShow::Ao        ? 1
                 : show_ == GiShow::Picture   ? 2
                 : show_ == GiShow::Heat      ? 3
                                              : 4;
  show_program_->set("u_mode", mode);
  show_program_->set("u_exposure", exposure_);
  show_program_->set("u_heat", heat_ > 0.f ? heat_ : 1.f);
  show_program_->set("u_picture_offset", guard_);
  const bool picture = show_ == GiShow::Picture || show_ == GiShow::Heat;
  glBindTextureUnit(slots().unit(0), picture ? picture_.id() : ran_ ? ssgi_.texture() : 0);
  const BackFaceTextures layer = back_.textures();
  glBindTextureUnit(slots().unit(1), drew_back_ ? layer.albedo : 0);
  glBindTextureUnit(slots().unit(2), drew_back_ ? layer.light : 0);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glBindVertexArray(vao_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindTextureUnit(slots().unit(1), 0);
  glBindTextureUnit(slots().unit(2), 0);
  return true;
}

}  // namespace lp::ch08
