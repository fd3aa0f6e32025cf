#include "chapters/02_gbuffer/gbuffer.h"
#include "chapters/01_forward/material.h"

#include <algorithm>

#include "chapters/01_forward/blinn_phong.h"
#include "chapters/02_gbuffer/depth.h"
#include "common/error.h"

namespace lp::ch02 {

namespace {

gl::Texture make_target(GLenum format, int w, int h, int samples = 1) {
  gl::Texture t = gl::make_render_texture(format, w, h, samples);
  if (samples > 1) return t;  // a multisampled texture has no sampler state: texelFetch only
  glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(t.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return t;
}

}  // namespace

// [gbuffer-targets]
GBuffer::GBuffer(int width, int height, const Layout& layout, int samples)
    : width_(width), height_(height), layout_(layout), samples_(samples),
      albedo_(make_target(layout.colour_format, width, height, samples)),
      specular_(make_target(layout.colour_format, width, height, samples)),
      normal_(make_target(normal_format(layout.normal), width, height, samples)),
      depth_stencil_(make_target(depth_format(layout.depth), width, height, samples)),
      extra_(layout.depth_target      ? make_target(GL_R32F, width, height, samples)
             : layout.stored_position ? make_target(GL_RGBA32F, width, height, samples)
                                      : gl::Texture(GL_TEXTURE_2D)),
      frame_(gl::make_buffer(nullptr, sizeof(GBufferFrame), GL_DYNAMIC_STORAGE_BIT)) {
  if (width <= 0 || height <= 0) throw Error("a G-buffer needs at least one pixel");
  if (samples < 1) throw Error("a G-buffer needs at least one sample per pixel (asked for " + std::to_string(samples) + ")");
  // Sampling the depth-stencil texture returns depth (not stencil).
  glTextureParameteri(depth_stencil_.id(), GL_DEPTH_STENCIL_TEXTURE_MODE, GL_DEPTH_COMPONENT);
  GLuint fbo = fbo_.id();
  glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, albedo_.id(), 0);
  glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT1, specular_.id(), 0);
  glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT2, normal_.id(), 0);
  const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};
  int count = 3;
  if (layout.depth_target || layout.stored_position) {
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT3, extra_.id(), 0);
    count = 4;
  }
  glNamedFramebufferDrawBuffers(fbo, count, buffers);  // fragment outputs 0..count-1
  glNamedFramebufferTexture(fbo, GL_DEPTH_STENCIL_ATTACHMENT, depth_stencil_.id(), 0);
  if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Error("the G-buffer framebuffer (layout " + layout.name + ", " + std::to_string(width) + "x" +
                std::to_string(height) + ", " + std::to_string(samples) + " samples) is incomplete on this driver");
  set_frame(FrameCamera{}, {});
}
// [/gbuffer-targets]

float GBuffer::sky_depth() const { return is_reversed_z(layout_) ? 0.f : 1.f; }

// [gbuffer-clear]
void GBuffer::bind_for_geometry() const {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
  glViewport(0, 0, width_, height_);
  glDisable(GL_SCISSOR_TEST);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  glStencilMask(0xFF);
  // Zero everywhere means "no geometry": control bits 0, emissive code 0, and the depth
  // buffer at its far value, which no drawn fragment can have (it would fail the test).
  // (The source's depth copy is cleared to the far value too, as the thesis does.)
  const float zero[4] = {0, 0, 0, 0}, far[4] = {sky_depth(), 0, 0, 0};
  for (int i = 0; i < 3; ++i) glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, i, zero);
  if (layout_.depth_target || layout_.stored_position)
    glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 3, layout_.depth_target ? far : zero);
  glClearNamedFramebufferfi(fbo_.id(), GL_DEPTH_STENCIL, 0, sky_depth(), 0);
}
// [/gbuffer-clear]

void GBuffer::bind_textures(GLuint first_unit) const {
  glBindTextureUnit(first_unit + 0, albedo_.id());
  glBindTextureUnit(first_unit + 1, specular_.id());
  glBindTextureUnit(first_unit + 2, normal_.id());
  glBindTextureUnit(first_unit + 3, layout_.depth_target ? extra_.id() : depth_stencil_.id());
  glBindTextureUnit(first_unit + 4, layout_.stored_position ? extra_.id() : 0);
  glBindBufferBase(GL_UNIFORM_BUFFER, kFrameBinding, frame_.id());
}

// [gbuffer-defines]
std::vector<std::string> gbuffer_defines(const Layout& layout, GLuint first_unit, int samples) {
  std::vector<std::string> d = {"GBUFFER_FIRST_UNIT " + std::to_string(first_unit),
                                "GBUFFER_FRAME_BINDING " + std::to_string(GBuffer::kFrameBinding)};
  if (samples > 1) d.push_back("GBUFFER_SAMPLES " + std::to_string(samples));  // chapter 10's MSAA
  switch (layout.normal) {
    case NormalEncoding::Float: d.push_back("GBUFFER_NORMAL_FLOAT 1"); break;
    case NormalEncoding::Xyz10: d.push_back("GBUFFER_NORMAL_XYZ 10"); break;
    case NormalEncoding::Oct8: d.push_back("GBUFFER_NORMAL_OCT 8"); break;
    case NormalEncoding::Oct10: d.push_back("GBUFFER_NORMAL_OCT 10"); break;
    case NormalEncoding::Oct16: d.push_back("GBUFFER_NORMAL_OCT 16"); break;
  }
  if (has_control_bits(layout)) d.push_back("GBUFFER_CONTROL_BITS 1");
  if (is_reversed_z(layout)) d.push_back("GBUFFER_REVERSED_Z 1");
  if (layout.depth_target) d.push_back("GBUFFER_DEPTH_COPY 1");
  if (layout.stored_position) d.push_back("GBUFFER_STORED_POSITION 1");
  if (layout.colour_format == GL_RGBA32F) d.push_back("GBUFFER_FLOAT_EXPONENT 1");
  if (layout.emissive == EmissiveStorage::AlbedoScale) d.push_back("GBUFFER_EMISSIVE_ALBEDO_SCALE 1");
  return d;
}
// [/gbuffer-defines]

std::vector<std::string> GBuffer::shader_defines(GLuint first_unit) const { return gbuffer_defines(layout_, first_unit, samples_); }

void GBuffer::set_frame(const FrameCamera& camera, const std::vector<glm::vec3>& palette, float emissive_scale) {
  camera_ = camera_for(layout_.depth, camera);
  GBufferFrame f{};
  f.gb_view_projection = camera_.view_projection();
  f.gb_inverse_view_projection = precise_inverse(f.gb_view_projection);
  f.gb_eye = glm::vec4(camera_.position, 1.f);
  f.gb_size = glm::vec4(width_, height_, 1.f / width_, 1.f / height_);
  f.gb_depth_info = glm::vec4(camera_.znear, camera_.zfar, sky_depth(), is_reversed_z(layout_) ? 1.f : 0.f);
  for (std::size_t i = 0; i < palette.size() && i < kPaletteSize; ++i) f.gb_emissive[i] = glm::vec4(palette[i] * emissive_scale, 0.f);
  glNamedBufferSubData(frame_.id(), 0, sizeof(GBufferFrame), &f);
}

// [depth-convention]
void GBuffer::begin_depth_convention() const {
  if (is_reversed_z(layout_)) {
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);  // clip z / w is the depth, no (z + 1) / 2
    glDepthFunc(GL_GREATER);                        // nearer is larger
  } else {
    glDepthFunc(GL_LESS);
  }
}

void GBuffer::restore_default_depth_convention() {
  glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
  glDepthFunc(GL_LESS);
}
// [/depth-convention]

GeometryPass::GeometryPass(const SceneGpu& scene) : scene_(scene) {
  // Code 0 means "not emissive"; each emissive material gets the next code.
  palette_.push_back(glm::vec3(0));
  for (const auto& m : scene.scene().materials) {
    bool emissive = m.emissive != glm::vec3(0);
    if (emissive && palette_.size() >= std::size_t(kPaletteSize))
      throw Error("scene has more than " + std::to_string(kPaletteSize - 1) + " emissive materials: the G-buffer's 8-bit emissive code cannot name them all");
    material_codes_.push_back(emissive ? int(palette_.size()) : 0);
    if (emissive) palette_.push_back(m.emissive);
  }
}

void GeometryPass::reload_shaders() {
  for (auto& [name, program] : programs_) program.reload();
}

const ShaderProgram& GeometryPass::program_for(const Layout& layout) {
  auto it = programs_.find(layout.name);
  if (it == programs_.end()) {
    it = programs_.emplace(layout.name, ShaderProgram({{GL_VERTEX_SHADER, "01_forward/shaders/forward.vert"},
                                                       {GL_FRAGMENT_SHADER, "02_gbuffer/shaders/geometry.frag"}},
                                                      gbuffer_defines(layout))).first;
  }
  return it->second;
}

// [geometry-pass]
void GeometryPass::draw(GBuffer& gbuffer, const FrameCamera& camera) {
  const ShaderProgram& program = program_for(gbuffer.layout());
  gbuffer.set_frame(camera, palette_, emissive_scale_);
  gbuffer.bind_for_geometry();
  gbuffer.begin_depth_convention();
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glEnable(GL_FRAMEBUFFER_SRGB);  // sRGB targets encode what the shader writes

  program.use();
  program.set("u_view_projection", gbuffer.camera().view_projection());
  const Material* first_material = scene_.scene().materials.data();
  scene_.draw([&](const Instance& inst, const Material& m) {
    ch01::set_surface(program, scene_, inst, m);  // chapter 01's material.h
    program.set("u_emissive_code", emissive_code(static_cast<int>(&m - first_material)));
    float base = std::max({m.base_color.r, m.base_color.g, m.base_color.b, 1e-6f});
    const glm::vec3 e = m.emissive * emissive_scale_;
    program.set("u_emissive_strength", std::clamp(std::max({e.r, e.g, e.b}) / base, 0.f, 1.f));
  }, SceneGpu::Primitives::Opaque);  // glass (alphaMode BLEND) is drawn after the deferred passes
  GBuffer::restore_default_depth_convention();
}
// [/geometry-pass]

}  // namespace lp::ch02
