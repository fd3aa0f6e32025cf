#include "chapters/02_gbuffer/deferred.h"

#include "common/error.h"

namespace lp::ch02 {

namespace {

const ShaderProgram& program_for(std::map<std::string, ShaderProgram>& programs, const GBuffer& gbuffer,
                                 const char* fragment) {
  auto it = programs.find(gbuffer.layout().name);
  if (it == programs.end())
    it = programs.emplace(gbuffer.layout().name,
                          ShaderProgram({{GL_VERTEX_SHADER, "02_gbuffer/shaders/fullscreen.vert"}, {GL_FRAGMENT_SHADER, fragment}},
                                        gbuffer.shader_defines(DeferredLighting::kFirstUnit))).first;
  return it->second;
}

void full_screen_state() {
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
}

void restore_state() {
  glDepthMask(GL_TRUE);
  glEnable(GL_DEPTH_TEST);
}

}  // namespace

void FullScreenPass::draw() const {
  glBindVertexArray(empty_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

// [lighting-pass]
void DeferredLighting::draw(const GBuffer& gbuffer, const ch01::LightBuffer& lights, const glm::vec3& ambient,
                            const glm::vec3& background, LightSelection selection) {
  const ShaderProgram& program = program_for(programs_, gbuffer, "02_gbuffer/shaders/deferred.frag");
  full_screen_state();
  gbuffer.bind_textures(kFirstUnit);
  lights.bind();
  program.use();
  program.set("u_ambient", ambient);
  program.set("u_background", background);
  program.set("u_light_count", lights.count());
  program.set("u_directional_only", int(selection == LightSelection::AmbientAndDirectional));
  quad_.draw();  // one fragment per pixel, whatever the scene's depth complexity
  restore_state();
}
// [/lighting-pass]

void DeferredLighting::reload_shaders() {
  for (auto& [name, p] : programs_) p.reload();
}

bool is_buffer_view(const std::string& name) {
  for (const auto& v : kBufferViews) if (v == name) return true;
  return false;
}

BufferView buffer_view(const std::string& name) {
  for (size_t i = 0; i < kBufferViews.size(); ++i)
    if (kBufferViews[i] == name) return static_cast<BufferView>(i);
  throw Error("unknown G-buffer view '" + name + "'");
}

void BufferViewPass::draw(const GBuffer& gbuffer, BufferView view, const glm::vec3& background) {
  const ShaderProgram& program = program_for(programs_, gbuffer, "02_gbuffer/shaders/buffer_view.frag");
  full_screen_state();
  gbuffer.bind_textures(DeferredLighting::kFirstUnit);
  program.use();
  program.set("u_view", static_cast<int>(view));
  program.set("u_background", background);
  quad_.draw();
  restore_state();
}

void BufferViewPass::reload_shaders() {
  for (auto& [name, p] : programs_) p.reload();
}

}  // namespace lp::ch02
