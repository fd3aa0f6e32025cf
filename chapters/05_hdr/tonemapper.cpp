#include "chapters/05_hdr/tonemapper.h"

#include "chapters/05_hdr/hdr_pipeline.h"

namespace lp::ch05 {

Tonemapper::Tonemapper()
    : program_({{GL_VERTEX_SHADER, "02_gbuffer/shaders/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "05_hdr/shaders/tonemap.frag"}}) {
  glSamplerParameteri(bilinear_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glSamplerParameteri(bilinear_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glSamplerParameteri(bilinear_.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glSamplerParameteri(bilinear_.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

void Tonemapper::draw(GLuint radiance, int w, int h, GLuint exposure_buffer, const TonemapSettings& s,
                      const BloomInput& bloom, GLuint output_framebuffer) const {
  glBindFramebuffer(GL_FRAMEBUFFER, output_framebuffer);
  glViewport(0, 0, w, h);
  glEnable(GL_FRAMEBUFFER_SRGB);  // linear out of the shader, sRGB in an sRGB8 target
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glBindTextureUnit(0, radiance);
  glBindTextureUnit(1, bloom.texture);
  glBindSampler(1, bilinear_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kExposureBinding, exposure_buffer);
  program_.use();
  program_.set("u_operator", int(s.op));
  program_.set("u_white", s.white);
  program_.set("u_bloom_mode", bloom.texture ? int(bloom.mode) : 0);
  program_.set("u_bloom_strength", bloom.strength);
  program_.set("u_bloom_threshold", bloom.threshold);
  program_.set("u_bloom_limit", bloom.limit);
  program_.set("u_bloom_uv_scale", bloom.uv_scale);
  program_.set("u_view", int(bloom.show_alone));
  glBindVertexArray(empty_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindSampler(1, 0);
  glEnable(GL_DEPTH_TEST);
}

}  // namespace lp::ch05
