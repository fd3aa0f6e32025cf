#pragma once
// Chapter 02's G-buffer: the targets one geometry pass fills (MRT) and everything a
// lighting pass needs to read them back. Later chapters link lightpass_02_gbuffer and
// include shaders/gbuffer.glsl; this is the contract they rely on:
//
// [contract]
//   GBuffer gbuffer(width, height);               // our layout; or GBuffer(w, h, layout_named("source"))
//   GeometryPass geometry(scene_gpu);
//   geometry.draw(gbuffer, frame.camera);         // clears, then draws the scene in one pass
//   ShaderProgram lighting({... "03_x/shaders/y.frag" ...}, gbuffer.shader_defines(first_unit));
//   glBindFramebuffer(...);                       // your own target
//   gbuffer.bind_textures(first_unit);            // texture units first_unit .. first_unit + 4,
//                                                 // and the GBufferFrame uniform block
//   // GLSL: #include "02_gbuffer/shaders/gbuffer.glsl"
//   //       Surface s = decode_gbuffer(ivec2(gl_FragCoord.xy));  // or decode_gbuffer(uv)
//   //       if (s.is_sky) ...; s.position / s.normal are world space, s.normal unit length
// [/contract]
//
// - Texture units: first_unit + 0 albedo (RGB albedo, A emissive code), + 1 specular (RGB
//   colour, A exponent code), + 2 normal, + 3 depth (the depth-stencil texture, or the
//   source layout's R32F copy), + 4 world position (float layout only). Sampled with
//   texelFetch, never filtered.
// - Uniform block GBufferFrame at binding kFrameBinding: the view-projection the G-buffer
//   was drawn with and its inverse, the eye, the size, the depth convention, and the
//   emissive palette. GeometryPass::draw writes it; bind_textures binds it.
// - Depth-stencil: GL_DEPTH24_STENCIL8 or GL_DEPTH32F_STENCIL8 (depth_stencil()), attached
//   to framebuffer() as GL_DEPTH_STENCIL_ATTACHMENT. The geometry pass clears stencil to 0
//   and never writes it: it is the later chapters' to use.
// - Depth convention: standard OpenGL depth (cleared to 1, test LESS) except in reversed-Z
//   layouts (cleared to 0, test GREATER, 1 at the near plane, glClipControl(GL_LOWER_LEFT,
//   GL_ZERO_TO_ONE)). To depth-test against this buffer draw with camera() and between
//   begin_depth_convention() and restore_default_depth_convention(). Every function here
//   leaves OpenGL's defaults (GL_NEGATIVE_ONE_TO_ONE, GL_LESS) behind.
// - Sky (no geometry): Surface.is_sky; its other fields are finite (zero, position on the
//   far plane), never NaN.
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "chapters/02_gbuffer/layout.h"
#include "common/camera.h"
#include "common/gl.h"
#include "common/scene_gpu.h"
#include "common/shader.h"

namespace lp::ch02 {

// `uniform GBufferFrame` of shaders/gbuffer.glsl, from the header both languages include.
namespace glsl {
using glm::mat4;
using glm::vec4;
struct GBufferFrame {
#include "chapters/02_gbuffer/shaders/gbuffer_frame.h"
};
}  // namespace glsl
using glsl::GBufferFrame;
inline constexpr int kPaletteSize = GBUFFER_PALETTE_SIZE;
static_assert(offsetof(GBufferFrame, gb_eye) == 128 && offsetof(GBufferFrame, gb_emissive) == 176 &&
                  sizeof(GBufferFrame) == 176 + 16 * kPaletteSize,
              "std140: two mat4, three vec4, the palette");

// The #defines gbuffer.glsl (and the geometry pass) need for a layout, e.g.
// {"GBUFFER_FIRST_UNIT 0", "GBUFFER_NORMAL_OCT 16", ...}.
std::vector<std::string> gbuffer_defines(const Layout& layout, GLuint first_unit = 0, int samples = 1);

class GBuffer {
 public:
  static constexpr GLuint kFrameBinding = 7;  // layout(std140, binding = 7) uniform GBufferFrame
  static constexpr int kUnits = 5;            // texture units used from first_unit on

  // `samples` > 1: every target multisampled (GL_TEXTURE_2D_MULTISAMPLE, chapter 10's MSAA),
  // and shader_defines() adds GBUFFER_SAMPLES so gbuffer.glsl reads them as sampler2DMS.
  GBuffer(int width, int height, const Layout& layout = our_layout(), int samples = 1);

  int width() const { return width_; }
  int height() const { return height_; }
  int samples() const { return samples_; }
  const Layout& layout() const { return layout_; }
  std::size_t bytes_per_pixel() const { return ch02::bytes_per_pixel(layout_); }

  GLuint framebuffer() const { return fbo_.id(); }
  GLuint albedo() const { return albedo_.id(); }
  GLuint specular() const { return specular_.id(); }
  GLuint normal() const { return normal_.id(); }
  GLuint depth_stencil() const { return depth_stencil_.id(); }
  GLuint depth_copy() const { return extra_.id() && layout_.depth_target ? extra_.id() : 0; }  // source layout
  GLuint position() const { return extra_.id() && layout_.stored_position ? extra_.id() : 0; }  // float layout

  // Binds the framebuffer for the geometry pass and clears every target to "no geometry":
  // colours and control bits 0, depth to the far value, stencil 0.
  void bind_for_geometry() const;
  // Binds the textures to first_unit.. and the frame block (see the contract above).
  void bind_textures(GLuint first_unit = 0) const;
  // gbuffer_defines(layout(), first_unit): what gbuffer.glsl needs for this layout.
  std::vector<std::string> shader_defines(GLuint first_unit = 0) const;

  // The camera of the last geometry pass, with the projection of this depth format.
  const FrameCamera& camera() const { return camera_; }
  float sky_depth() const;  // the clear value: 1, or 0 with reversed-Z
  void begin_depth_convention() const;        // reversed-Z: clip control 0..1, GREATER
  static void restore_default_depth_convention();  // OpenGL's -1..1 and LESS

  // Called by GeometryPass::draw: the camera it draws with and the emissive colours.
  // The palette is written times `emissive_scale` (GeometryPass::set_emissive_scale).
  void set_frame(const FrameCamera& camera, const std::vector<glm::vec3>& emissive_palette, float emissive_scale = 1.f);

 private:
  int width_, height_;
  Layout layout_;
  int samples_;
  gl::Framebuffer fbo_;
  gl::Texture albedo_, specular_, normal_, depth_stencil_, extra_;
  gl::Buffer frame_;
  FrameCamera camera_;
};

// The geometry pass: every instance drawn once into all targets (multiple render targets),
// normal-mapped through the tangents, encoded for the layout.
class GeometryPass {
 public:
  explicit GeometryPass(const SceneGpu& scene);
  void reload_shaders();

  // Clears `gbuffer` and draws the scene into it as seen by `camera` (a standard OpenGL
  // camera; reversed-Z layouts swap the projection themselves). Leaves the G-buffer's
  // framebuffer bound, depth test on with OpenGL's default convention.
  void draw(GBuffer& gbuffer, const FrameCamera& camera);
  // Every emissive colour times `scale` when it is drawn (chapter 05's glow: a frame
  // parameter, so the scene is never copied to change it).
  void set_emissive_scale(float scale) { emissive_scale_ = scale; }
  float emissive_scale() const { return emissive_scale_; }

  // Colour of each emissive code (index 0: none), and each material's code.
  const std::vector<glm::vec3>& emissive_palette() const { return palette_; }
  int emissive_code(int material) const { return material_codes_[material]; }

 private:
  const ShaderProgram& program_for(const Layout& layout);
  const SceneGpu& scene_;
  std::vector<glm::vec3> palette_;
  std::vector<int> material_codes_;
  float emissive_scale_ = 1.f;
  std::map<std::string, ShaderProgram> programs_;  // one per layout, made when first needed
};

}  // namespace lp::ch02
