#include "chapters/11_temporal/motion.h"

#include "common/error.h"

namespace lp::ch11 {

MotionStage::MotionStage(const SceneGpu& scene)
    : scene_(scene),
      object_pass_({{GL_VERTEX_SHADER, "11_temporal/shaders/motion_object.vert"},
                    {GL_FRAGMENT_SHADER, "11_temporal/shaders/motion_object.frag"}}) {}

void MotionStage::reload_shaders() {
  object_pass_.reload();
  if (camera_pass_) camera_pass_->reload();
}

void MotionStage::set_cameras(const FrameCamera& current, const FrameCamera& previous) {
  current_ = current;
  previous_ = previous;
}

void MotionStage::set_previous_models(std::vector<glm::mat4> models) {
  if (!models.empty() && models.size() != scene_.scene().instances.size())
    throw Error("motion: " + std::to_string(models.size()) + " previous model matrices for a scene of " +
                std::to_string(scene_.scene().instances.size()) + " instances");
  previous_models_ = std::move(models);
}

void MotionStage::resize(int width, int height) {
  width_ = width;
  height_ = height;
  frames_ = 0;
  for (int i = 0; i < 2; ++i) {
    targets_[i] = gl::make_texture_2d(GL_RGBA32F, width, height);
    colour_only_[i] = gl::Framebuffer();
    glNamedFramebufferTexture(colour_only_[i].id(), GL_COLOR_ATTACHMENT0, targets_[i].id(), 0);
    with_depth_[i] = gl::Framebuffer();
    glNamedFramebufferTexture(with_depth_[i].id(), GL_COLOR_ATTACHMENT0, targets_[i].id(), 0);
    attached_depth_[i] = 0;
  }
}

// [motion-pass]
void MotionStage::before_lights(ch03::DeferredFrame& frame, PassMetrics* metrics) {
  if (!enabled_) return;
  auto pass = timed(metrics, "motion vectors");
  const ch02::GBuffer& gbuffer = frame.gbuffer();
  if (gbuffer.width() != width_ || gbuffer.height() != height_) resize(gbuffer.width(), gbuffer.height());
  cur_ = 1 - cur_;
  frames_ = std::min(frames_ + 1, 2);
  if (!camera_pass_)  // made when the G-buffer's layout is known
    camera_pass_ = std::make_unique<ShaderProgram>(std::vector<ShaderStage>{{GL_VERTEX_SHADER, "02_gbuffer/shaders/fullscreen.vert"},
                                  {GL_FRAGMENT_SHADER, "11_temporal/shaders/motion_camera.frag"}},
                                 gbuffer.shader_defines(0));
  const glm::mat4 now = current_.view_projection(), then = previous_.view_projection();
  // 1. Every pixel moved by the camera: reads the G-buffer, so its depth is not attached.
  glBindFramebuffer(GL_FRAMEBUFFER, colour_only_[cur_].id());
  glViewport(0, 0, width_, height_);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_FRAMEBUFFER_SRGB);
  gbuffer.bind_textures(0);
  camera_pass_->use();
  camera_pass_->set("u_current_view_projection", now);
  camera_pass_->set("u_previous_view_projection", then);
  glBindVertexArray(empty_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  // 2. The opaque objects again, each with its own last model matrix, where the G-buffer's
  //    depth says they are visible (its depth attached, tested, never written).
  if (attached_depth_[cur_] != gbuffer.depth_stencil()) {
    glNamedFramebufferTexture(with_depth_[cur_].id(), GL_DEPTH_STENCIL_ATTACHMENT, gbuffer.depth_stencil(), 0);
    attached_depth_[cur_] = gbuffer.depth_stencil();
  }
  glBindFramebuffer(GL_FRAMEBUFFER, with_depth_[cur_].id());
  gbuffer.begin_depth_convention();
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(gbuffer.sky_depth() == 0.f ? GL_GEQUAL : GL_LEQUAL);  // the same depth passes
  glDepthMask(GL_FALSE);
  glEnable(GL_CULL_FACE);
  object_pass_.use();
  object_pass_.set("u_view_projection", gbuffer.camera().view_projection());
  object_pass_.set("u_current_view_projection", now);
  object_pass_.set("u_previous_view_projection", then);
  const Instance* first = scene_.scene().instances.data();
  scene_.draw([&](const Instance& inst, const Material&) {
    const std::size_t i = std::size_t(&inst - first);
    object_pass_.set("u_model", inst.model);
    object_pass_.set("u_previous_model", previous_models_.empty() ? inst.model : previous_models_[i]);
  }, SceneGpu::Primitives::Opaque);
  glDepthMask(GL_TRUE);
  ch02::GBuffer::restore_default_depth_convention();
}
// [/motion-pass]

}  // namespace lp::ch11
