#include "chapters/01_forward/forward.h"
#include "chapters/01_forward/material.h"

#include "chapters/01_forward/blinn_phong.h"
#include "common/error.h"

namespace lp::ch01 {

ForwardMode forward_mode(const std::string& name) {
  for (size_t i = 0; i < kForwardModes.size(); ++i)
    if (kForwardModes[i] == name) return static_cast<ForwardMode>(i);
  throw Error("unknown forward mode '" + name + "'");
}

ForwardRenderer::ForwardRenderer(const SceneGpu& scene)
    : scene_(scene),
      per_pixel_({{GL_VERTEX_SHADER, "01_forward/shaders/forward.vert"}, {GL_FRAGMENT_SHADER, "01_forward/shaders/forward.frag"}}),
      per_vertex_({{GL_VERTEX_SHADER, "01_forward/shaders/forward.vert"}, {GL_FRAGMENT_SHADER, "01_forward/shaders/forward.frag"}},
                  {"PER_VERTEX 1"}) {}

void ForwardRenderer::reload_shaders() {
  per_pixel_.reload();
  per_vertex_.reload();
}

void ForwardRenderer::draw_scene(const ShaderProgram& program, const FrameCamera& camera, bool renormalize,
                                 bool include_base, int first_light, int light_count) const {
  program.use();
  program.set("u_view_projection", camera.view_projection());
  program.set("u_eye", camera.position);
  program.set("u_ambient", scene_.scene().ambient);
  program.set("u_renormalize", int(renormalize));
  program.set("u_include_base", int(include_base));
  program.set("u_first_light", first_light);
  program.set("u_light_count", light_count);
  // [per-draw]
  scene_.draw([&](const Instance& inst, const Material& m) {
    set_surface(program, scene_, inst, m, emissive_scale_);  // material.h: the same in every pass
  });
  // [/per-draw]
}

void ForwardRenderer::draw(const FrameCamera& camera, ForwardMode mode, const LightBuffer& lights) const {
  if (mode == ForwardMode::MultiPass) throw Error("internal: multi-pass is drawn with draw_base + draw_additive_lights");
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glEnable(GL_CULL_FACE);
  lights.bind();
  const ShaderProgram& program = mode == ForwardMode::PerVertex ? per_vertex_ : per_pixel_;
  draw_scene(program, camera, mode != ForwardMode::PerPixelUnnormalized, true, 0, lights.count());
}

void ForwardRenderer::draw_base(const FrameCamera& camera, const LightBuffer& lights) const {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glEnable(GL_CULL_FACE);
  lights.bind();
  draw_scene(per_pixel_, camera, true, true, 0, 0);
}

// [additive-passes]
void ForwardRenderer::draw_additive_lights(const FrameCamera& camera, const LightBuffer& lights) const {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_EQUAL);   // only the visible surface, found by the base pass
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);  // each light adds its contribution
  lights.bind();
  for (int i = 0; i < lights.count(); ++i) draw_scene(per_pixel_, camera, true, false, i, 1);
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
}
// [/additive-passes]

}  // namespace lp::ch01
