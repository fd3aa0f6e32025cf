// Chapter 06's convolution shadow maps (csm_math.h): the sun's depth map turned into the basis
// of the step's Fourier series and box-filtered, by ShadowStage before the lights;
// shadow_visibility.glsl [csm-glsl] reconstructs the step from it.
#include <string>

#include "chapters/06_shadows/shadow_stage.h"
#include "common/error.h"

namespace lp::ch06 {

// [csm-stage]
void ShadowStage::filter_csm(PassMetrics* metrics, GLuint depth_unit, GLuint input_unit) {
  const int n = settings_.map_size, terms = settings_.csm_terms;
  if (terms < 1 || terms > kMaxCsmTerms)
    throw Error("shadow stage: csm_terms must be between 1 and " + std::to_string(kMaxCsmTerms) + " (got " +
                std::to_string(terms) + ")");
  const int layers = (terms + 1) / 2;  // two terms, four values, a layer
  if (n != csm_size_ || layers != csm_layers_) {
    csm_maps_ = gl::Texture(GL_TEXTURE_2D_ARRAY), csm_scratch_ = gl::Texture(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(csm_maps_.id(), 1, GL_RGBA32F, n, n, layers);
    glTextureStorage3D(csm_scratch_.id(), 1, GL_RGBA32F, n, n, layers);
    csm_fbo_ = gl::Framebuffer(), csm_scratch_fbo_ = gl::Framebuffer();
    std::vector<GLenum> buffers;
    for (int i = 0; i < layers; ++i) {
      glNamedFramebufferTextureLayer(csm_fbo_.id(), GLenum(GL_COLOR_ATTACHMENT0 + i), csm_maps_.id(), 0, i);
      glNamedFramebufferTextureLayer(csm_scratch_fbo_.id(), GLenum(GL_COLOR_ATTACHMENT0 + i), csm_scratch_.id(), 0, i);
      buffers.push_back(GLenum(GL_COLOR_ATTACHMENT0 + i));
    }
    glNamedFramebufferDrawBuffers(csm_fbo_.id(), GLsizei(layers), buffers.data());
    glNamedFramebufferDrawBuffers(csm_scratch_fbo_.id(), GLsizei(layers), buffers.data());
    csm_size_ = n, csm_layers_ = layers;
  }
  auto pass = timed(metrics, "shadow map: pre-filter");  // the sweep's filter_ms column, as VSM's
  const ShaderProgram& p = program("02_gbuffer/shaders/fullscreen.vert", "06_shadows/shaders/csm_filter.frag", {});
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  p.use();
  p.set("u_radius", settings_.kernel / 2);
  p.set("u_terms", terms);
  // On the stage's own units, never the frame's (the G-buffer's stay bound for the lights); the
  // hooks' textures are bound again on them before each light pass.
  glUniform1i(p.location("u_depth"), int(depth_unit));
  glUniform1i(p.location("u_input"), int(input_unit));
  glBindTextureUnit(depth_unit, depth_.id());
  glBindSampler(depth_unit, 0);
  glBindTextureUnit(input_unit, csm_scratch_.id());
  glBindSampler(input_unit, 0);
  for (int step = 0; step < 2; ++step) {
    // 1. Horizontal, from the depths into the scratch array; 2. vertical, from it into the maps.
    glBindFramebuffer(GL_FRAMEBUFFER, step == 0 ? csm_scratch_fbo_.id() : csm_fbo_.id());
    glViewport(0, 0, n, n);
    p.set("u_from_depth", step == 0 ? 1 : 0);
    glProgramUniform2i(p.id(), p.location("u_step"), step == 0 ? 1 : 0, step == 0 ? 0 : 1);
    full_screen_.draw();
  }
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
}
// [/csm-stage]

}  // namespace lp::ch06
