#include "chapters/02_gbuffer/probe.h"

#include "common/error.h"

namespace lp::ch02 {

SurfaceImages SurfaceProbe::read(const GBuffer& gbuffer) {
  auto it = programs_.find(gbuffer.layout().name);
  if (it == programs_.end())
    it = programs_.emplace(gbuffer.layout().name,
                           ShaderProgram({{GL_VERTEX_SHADER, "02_gbuffer/shaders/fullscreen.vert"},
                                          {GL_FRAGMENT_SHADER, "02_gbuffer/shaders/probe.frag"}},
                                         gbuffer.shader_defines(DeferredLighting::kFirstUnit))).first;
  const int w = gbuffer.width(), h = gbuffer.height();
  constexpr int kFields = 5;
  gl::Texture textures[kFields] = {gl::make_texture_2d(GL_RGBA32F, w, h), gl::make_texture_2d(GL_RGBA32F, w, h),
                                   gl::make_texture_2d(GL_RGBA32F, w, h), gl::make_texture_2d(GL_RGBA32F, w, h),
                                   gl::make_texture_2d(GL_RGBA32F, w, h)};
  gl::Framebuffer fbo;
  GLenum buffers[kFields];
  for (int i = 0; i < kFields; ++i) {
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0 + i, textures[i].id(), 0);
    buffers[i] = GL_COLOR_ATTACHMENT0 + i;
  }
  glNamedFramebufferDrawBuffers(fbo.id(), kFields, buffers);
  if (glCheckNamedFramebufferStatus(fbo.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Error("the surface probe's framebuffer is incomplete");
  glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
  glViewport(0, 0, w, h);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  gbuffer.bind_textures(DeferredLighting::kFirstUnit);
  it->second.use();
  quad_.draw();
  glEnable(GL_DEPTH_TEST);

  ImageF* out[kFields];
  SurfaceImages images;
  out[0] = &images.position; out[1] = &images.normal; out[2] = &images.albedo; out[3] = &images.specular; out[4] = &images.emissive;
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  for (int i = 0; i < kFields; ++i) {
    *out[i] = ImageF::blank(w, h, 4);
    glGetTextureImage(textures[i].id(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(out[i]->data.size() * sizeof(float)),
                      out[i]->data.data());
    flip_vertically(*out[i]);
  }
  return images;
}

}  // namespace lp::ch02
