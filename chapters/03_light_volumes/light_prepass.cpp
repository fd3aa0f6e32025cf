#include "chapters/03_light_volumes/light_prepass.h"
#include "chapters/01_forward/material.h"

#include "chapters/01_forward/blinn_phong.h"
#include "chapters/02_gbuffer/depth.h"
#include "common/error.h"

namespace lp::ch03 {

namespace {

// gbuffer.glsl's defines for the small G-buffer: chapter 02's layout "ours" (octahedral
// RG16 normal, standard depth, exponent code in the specular texture's alpha).
std::vector<std::string> prepass_defines() { return ch02::gbuffer_defines(ch02::our_layout(), 0); }

gl::Texture make_target(GLenum format, int w, int h) {
  gl::Texture t = gl::make_texture_2d(format, w, h);
  glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return t;
}

}  // namespace

LightPrePass::LightPrePass(const SceneGpu& scene)
    : scene_(scene),
      geometry_({{GL_VERTEX_SHADER, "01_forward/shaders/forward.vert"}, {GL_FRAGMENT_SHADER, "02_gbuffer/shaders/geometry.frag"}},
                prepass_defines()),
      material_({{GL_VERTEX_SHADER, "01_forward/shaders/forward.vert"},
                 {GL_FRAGMENT_SHADER, "03_light_volumes/shaders/prepass_material.frag"}}),
      frame_(gl::make_buffer(nullptr, sizeof(ch02::GBufferFrame), GL_DYNAMIC_STORAGE_BIT)) {}

void LightPrePass::reload_shaders() {
  geometry_.reload();
  material_.reload();
}

std::size_t LightPrePass::bytes_per_pixel() const {
  return gl::bytes_per_texel(kNormalFormat) + gl::bytes_per_texel(kExponentFormat) + gl::bytes_per_texel(kDepthFormat);
}

void LightPrePass::draw_geometry(const FrameCamera& camera, int width, int height) {
  if (width != width_ || height != height_) {
    width_ = width;
    height_ = height;
    normal_ = make_target(kNormalFormat, width, height);
    exponent_ = make_target(kExponentFormat, width, height);
    depth_ = make_target(kDepthFormat, width, height);
    glTextureParameteri(depth_.id(), GL_DEPTH_STENCIL_TEXTURE_MODE, GL_DEPTH_COMPONENT);
    fbo_ = gl::Framebuffer();
    glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT0, exponent_.id(), 0);
    glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT1, normal_.id(), 0);
    glNamedFramebufferTexture(fbo_.id(), GL_DEPTH_STENCIL_ATTACHMENT, depth_.id(), 0);
    // [prepass-targets]
    // Chapter 02's geometry shader writes albedo (0), specular + exponent (1), normal (2):
    // the albedo goes nowhere, and of output 1 only the alpha (the exponent) is kept.
    const GLenum buffers[] = {GL_NONE, GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(fbo_.id(), 3, buffers);
    // [/prepass-targets]
    if (glCheckNamedFramebufferStatus(fbo_.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw Error("the light pre-pass G-buffer is incomplete on this driver");
  }
  camera_ = camera;
  ch02::GBufferFrame f{};
  f.gb_view_projection = camera.view_projection();
  f.gb_inverse_view_projection = ch02::precise_inverse(f.gb_view_projection);
  f.gb_eye = glm::vec4(camera.position, 1.f);
  f.gb_size = glm::vec4(width_, height_, 1.f / width_, 1.f / height_);
  f.gb_depth_info = glm::vec4(camera.znear, camera.zfar, 1.f, 0.f);
  glNamedBufferSubData(frame_.id(), 0, sizeof(f), &f);

  glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
  glViewport(0, 0, width_, height_);
  glDisable(GL_FRAMEBUFFER_SRGB);
  glDisable(GL_SCISSOR_TEST);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  glStencilMask(0xFF);
  const float zero[4] = {0, 0, 0, 0};
  glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 1, zero);
  glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 2, zero);
  glClearNamedFramebufferfi(fbo_.id(), GL_DEPTH_STENCIL, 0, 1.f, 0);
  glColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_TRUE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  geometry_.use();
  geometry_.set("u_view_projection", camera.view_projection());
  scene_.draw([&](const Instance& inst, const Material& m) {
    ch01::set_surface(geometry_, scene_, inst, m);  // chapter 01's material.h
  });
  glColorMaski(1, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDisable(GL_CULL_FACE);
}

SurfaceView LightPrePass::view() const { return {camera_, false, prepass_defines()}; }

void LightPrePass::bind_textures() const {
  // gbuffer.glsl's units: 0 albedo (none here: the exponent texture stands in, so the
  // reads are defined), 1 specular (its alpha: the exponent), 2 normal, 3 depth.
  glBindTextureUnit(0, exponent_.id());
  glBindTextureUnit(1, exponent_.id());
  glBindTextureUnit(2, normal_.id());
  glBindTextureUnit(3, depth_.id());
  glBindBufferBase(GL_UNIFORM_BUFFER, ch02::GBuffer::kFrameBinding, frame_.id());
}

// [second-geometry-pass]
void LightPrePass::draw_materials(const LightBuffer& light, PrePassSpecular specular) const {
  // The same triangles as pass 1 must find their own depths. forward.vert declares its
  // position invariant, yet two programs need not agree to the last bit (llvmpipe's do
  // not: depth test EQUAL rejects most pixels). One depth unit of offset towards the eye
  // and LEQUAL accept the nearest surface and still reject everything behind it.
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(0.f, -1.f);
  glDepthMask(GL_FALSE);
  glEnable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glBindTextureUnit(5, light.diffuse());
  material_.use();
  material_.set("u_view_projection", camera_.view_projection());
  material_.set("u_chroma", int(specular == PrePassSpecular::Chroma));
  scene_.draw([&](const Instance& inst, const Material& m) {
    ch01::set_surface(material_, scene_, inst, m);
  });
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
}
// [/second-geometry-pass]

// [prepass-frame]
void LightPrePass::render(LightVolumes& volumes, const LightBuffer& light, const FrameCamera& camera,
                          const FrameOutput& output, const glm::vec3& ambient, const glm::vec3& background,
                          PrePassSpecular specular, PassMetrics* metrics) {
  {
    auto pass = timed(metrics, "geometry 1: normal, exponent, depth");
    draw_geometry(camera, output.width, output.height);
  }
  bind_textures();
  light.begin(framebuffer());
  {
    auto pass = timed(metrics, "global: ambient + directional (chapter 03)");
    volumes.draw_global(light, view(), ambient);
  }
  {
    auto pass = timed(metrics, "local lights: stencil");
    volumes.draw_local(light, view(), Strategy::Stencil);
  }
  output.bind();
  glBlitNamedFramebuffer(framebuffer(), output.framebuffer, 0, 0, output.width, output.height, 0, 0, output.width,
                         output.height, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  glClearColor(background.r, background.g, background.b, 1.f);
  glClear(GL_COLOR_BUFFER_BIT);
  auto pass = timed(metrics, "geometry 2: materials x light");
  draw_materials(light, specular);
}
// [/prepass-frame]

}  // namespace lp::ch03
