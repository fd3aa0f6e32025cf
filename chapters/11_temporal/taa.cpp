#include "chapters/11_temporal/taa.h"

#include "common/error.h"

namespace lp::ch11 {

TaaStage::TaaStage(const MotionStage& motion)
    : motion_(motion),
      resolve_({{GL_VERTEX_SHADER, "02_gbuffer/shaders/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "11_temporal/shaders/taa_resolve.frag"}}) {
  glSamplerParameteri(bilinear_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glSamplerParameteri(bilinear_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glSamplerParameteri(bilinear_.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glSamplerParameteri(bilinear_.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

void TaaStage::resize(int width, int height) {
  width_ = width;
  height_ = height;
  rejected_ = gl::make_texture_2d(GL_R8, width, height);
  for (int i = 0; i < 2; ++i) {
    history_[i] = gl::make_texture_2d(GL_RGBA16F, width, height);
    box_lo_[i] = gl::make_texture_2d(GL_RGBA16F, width, height);
    box_hi_[i] = gl::make_texture_2d(GL_RGBA16F, width, height);
    fbo_[i] = gl::Framebuffer();
    glNamedFramebufferTexture(fbo_[i].id(), GL_COLOR_ATTACHMENT0, history_[i].id(), 0);
    glNamedFramebufferTexture(fbo_[i].id(), GL_COLOR_ATTACHMENT1, rejected_.id(), 0);
    glNamedFramebufferTexture(fbo_[i].id(), GL_COLOR_ATTACHMENT2, box_lo_[i].id(), 0);
    glNamedFramebufferTexture(fbo_[i].id(), GL_COLOR_ATTACHMENT3, box_hi_[i].id(), 0);
    const GLenum all[4] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};
    glNamedFramebufferDrawBuffers(fbo_[i].id(), 4, all);
  }
  reset_ = true;
}

// [taa-pass]
void TaaStage::after_composite(ch03::DeferredFrame& frame, PassMetrics* metrics) {
  if (!settings_.enabled) {
    reset_ = true;  // switched on again, it starts from the frame it gets
    return;
  }
  auto pass = timed(metrics, "TAA resolve");
  const ch03::FrameOutput& out = frame.output();
  GLint radiance = 0, format = 0;
  glGetNamedFramebufferAttachmentParameteriv(out.framebuffer, GL_COLOR_ATTACHMENT0, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &radiance);
  if (radiance > 0) glGetTextureLevelParameteriv(GLuint(radiance), 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
  if (radiance <= 0 || format != GL_RGBA16F)
    throw Error("TAA: the frame's output is not a float radiance texture (RGBA16F); draw it through chapter 05's radiance target");
  if (out.width != width_ || out.height != height_) resize(out.width, out.height);
  // No last frame to move (the first, after a cut or a resize): this frame alone.
  const bool reset = reset_ || motion_.previous() == 0;
  const int next = 1 - cur_;
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_[next].id());
  glViewport(0, 0, width_, height_);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_FRAMEBUFFER_SRGB);
  glBindTextureUnit(0, GLuint(radiance));
  glBindTextureUnit(1, history_[cur_].id());
  glBindSampler(1, bilinear_.id());
  glBindTextureUnit(2, motion_.current());
  glBindTextureUnit(3, reset ? motion_.current() : motion_.previous());
  glBindTextureUnit(4, box_lo_[cur_].id());
  glBindTextureUnit(5, box_hi_[cur_].id());
  resolve_.use();
  resolve_.set("u_alpha", settings_.alpha);
  resolve_.set("u_filter", int(settings_.filter));
  resolve_.set("u_clip", int(settings_.clip));
  resolve_.set("u_reject_disocclusion", int(settings_.reject_disocclusion));
  resolve_.set("u_depth_tolerance", settings_.depth_tolerance);
  resolve_.set("u_depth_slope", settings_.depth_slope);
  resolve_.set("u_tonemapped", int(settings_.tonemapped));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, exposure_state_);
  resolve_.set("u_has_exposure", int(exposure_state_ != 0));
  resolve_.set("u_reset", int(reset));
  resolve_.set("u_jitter", jitter_);
  resolve_.set("u_unjitter", int(settings_.unjitter));
  resolve_.set("u_gamma", settings_.gamma);
  resolve_.set("u_alpha_moving", settings_.alpha_moving);
  resolve_.set("u_box_keep", settings_.box_memory > 0 ? 1.f - 1.f / float(settings_.box_memory) : 0.f);
  glBindVertexArray(empty_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindSampler(1, 0);
  // The result is the frame's radiance from here on (the HDR chain reads it) and the next
  // frame's history.
  glCopyImageSubData(history_[next].id(), GL_TEXTURE_2D, 0, 0, 0, 0, GLuint(radiance), GL_TEXTURE_2D, 0, 0, 0, 0, width_, height_, 1);
  cur_ = next;
  reset_ = false;
  glEnable(GL_DEPTH_TEST);
  out.bind();
}
// [/taa-pass]

}  // namespace lp::ch11
