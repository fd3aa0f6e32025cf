#pragma once
// Deferred lighting, or the light pre-pass: the variant that keeps the G-buffer small. The
// first geometry pass stores only what lighting needs from the surface (normal, exponent,
// depth); the light volumes fill one light buffer (rgb: diffuse light, a: specular light as
// one number); a second geometry pass draws every object again and applies its material to
// the light. The price is that one number: a highlight cannot keep the colour of the light
// that made it.
#include <vector>

#include "chapters/02_gbuffer/gbuffer.h"
#include "chapters/03_light_volumes/deferred_frame.h"
#include "chapters/03_light_volumes/light_volumes.h"
#include "common/gl.h"
#include "common/scene_gpu.h"
#include "common/shader.h"

namespace lp::ch03 {

// How the second geometry pass colours the specular light it reads as one number.
enum class PrePassSpecular {
  White,   // as stored: white highlights whatever the light's colour
  Chroma,  // the colour of the diffuse light at the pixel (a mix where lights overlap)
};

class LightPrePass {
 public:
  explicit LightPrePass(const SceneGpu& scene);
  void reload_shaders();

  // [prepass-gbuffer]
  // The small G-buffer: chapter 02's octahedral RG16 normal, the exponent (8-bit code in
  // the alpha of an RGBA8: chapter 02's geometry shader writes it with the specular colour,
  // whose channels we mask off) and a D24S8 depth: 12 bytes a pixel against 16.
  static constexpr GLenum kNormalFormat = GL_RG16, kExponentFormat = GL_RGBA8, kDepthFormat = GL_DEPTH24_STENCIL8;
  // [/prepass-gbuffer]
  std::size_t bytes_per_pixel() const;

  // Pass 1: clears and fills the small G-buffer as seen by `camera`.
  void draw_geometry(const FrameCamera& camera, int width, int height);
  // What the light shaders read; binds the textures (units 0..3) and the frame block.
  SurfaceView view() const;
  void bind_textures() const;
  GLuint framebuffer() const { return fbo_.id(); }
  // Pass 3: every object again into the bound framebuffer, whose depth must hold a copy of
  // this G-buffer's (depth test EQUAL), lit by `light` (a LightBuffer of kind PrePass).
  void draw_materials(const LightBuffer& light, PrePassSpecular specular) const;

  // The whole deferred-lighting frame into `output`: pass 1, chapter 03's global and
  // stencil-masked local lights into `light` (of kind PrePass, this size), pass 2 over a copy
  // of pass 1's depth. Each pass timed in `metrics`.
  void render(LightVolumes& volumes, const LightBuffer& light, const FrameCamera& camera, const FrameOutput& output,
              const glm::vec3& ambient, const glm::vec3& background, PrePassSpecular specular,
              PassMetrics* metrics = nullptr);

 private:
  const SceneGpu& scene_;
  ShaderProgram geometry_, material_;
  int width_ = 0, height_ = 0;
  FrameCamera camera_;
  gl::Texture normal_{GL_TEXTURE_2D}, exponent_{GL_TEXTURE_2D}, depth_{GL_TEXTURE_2D};
  gl::Framebuffer fbo_;
  gl::Buffer frame_;
};

}  // namespace lp::ch03
