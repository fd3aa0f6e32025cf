#include "chapters/08_ssgi/back_faces.h"

#include "chapters/01_forward/material.h"

namespace lp::ch08 {

// [back-faces]
void BackFaceLayer::draw(const SceneGpu& scene, ch03::DeferredFrame& frame) {
  const ch02::GBuffer& front = frame.gbuffer();
  const ch02::Layout& layout = front.layout();
  if (!gbuffer_ || gbuffer_->width() != front.width() || gbuffer_->height() != front.height() ||
      gbuffer_->layout().name != layout.name) {
    gbuffer_ = std::make_unique<ch02::GBuffer>(front.width(), front.height(), layout);
    light_ = std::make_unique<ch03::LightBuffer>(front.width(), front.height(), ch02::depth_format(layout.depth));
  }
  if (!program_)
    program_ = std::make_unique<ShaderProgram>(
        std::vector<ShaderStage>{{GL_VERTEX_SHADER, "01_forward/shaders/forward.vert"},
                                 {GL_FRAGMENT_SHADER, "08_ssgi/shaders/back_faces.frag"}},
        ch02::gbuffer_defines(layout));
  // 1. The nearest back face per pixel: chapter 02's geometry pass with the front faces culled
  //    (SceneGpu::draw still turns the winding of mirrored instances and draws doubleSided
  //    materials unculled: back_faces.frag keeps only their far side).
  gbuffer_->set_frame(frame.camera(), {glm::vec3(0)});  // emissive code 0: a back face emits nothing
  gbuffer_->bind_for_geometry();
  gbuffer_->begin_depth_convention();
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_FRONT);
  glDisable(GL_BLEND);
  program_->use();
  program_->set("u_view_projection", gbuffer_->camera().view_projection());
  scene.draw([&](const Instance& inst, const Material& m) { ch01::set_surface(*program_, scene, inst, m); },
             SceneGpu::Primitives::Opaque);
  glCullFace(GL_BACK);
  ch02::GBuffer::restore_default_depth_convention();
  // 2. The light arriving there: chapter 03's global and local lights at the back faces, with
  //    the frame's hooks (its visibility: shadows, where a stage gives them), no ambient.
  gbuffer_->bind_textures(0);
  ch03::SurfaceView view = ch03::surface_view(*gbuffer_);
  view.hooks = frame.view().hooks;
  light_->begin(gbuffer_->framebuffer());
  frame.bind_hooks();
  frame.volumes().draw_global(*light_, view, glm::vec3(0));
  frame.volumes().draw_local(*light_, view, ch03::Strategy::Stencil);
  // 3. The frame's G-buffer where the passes after this one expect it
  front.bind_textures(0);
  frame.light().bind();
}
// [/back-faces]

BackFaceTextures BackFaceLayer::textures() const {
  if (!gbuffer_) return {};
  const GLuint depth = gbuffer_->layout().depth_target ? gbuffer_->depth_copy() : gbuffer_->depth_stencil();
  return {depth, gbuffer_->normal(), gbuffer_->albedo(), light_->diffuse()};
}

std::size_t BackFaceLayer::allocated_bytes() const {
  if (!gbuffer_) return 0;
  return gbuffer_->bytes_per_pixel() * std::size_t(gbuffer_->width()) * std::size_t(gbuffer_->height()) + light_->bytes();
}

}  // namespace lp::ch08
