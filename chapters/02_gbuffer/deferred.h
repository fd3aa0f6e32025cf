#pragma once
// The second half of deferred shading: full-screen passes that read the G-buffer. The
// lighting pass lights every pixel once with chapter 01's Blinn-Phong (ambient, emissive,
// and the lights: the directional ones only, or all of them to compare with chapter 01);
// the buffer views show what one target holds.
#include <map>
#include <string>
#include <vector>

#include "chapters/01_forward/light_buffer.h"
#include "chapters/02_gbuffer/gbuffer.h"
#include "common/gl.h"
#include "common/shader.h"

namespace lp::ch02 {

// Which lights the full-screen pass evaluates.
enum class LightSelection {
  All,                    // every light of the buffer, per pixel: the image of chapter 01
  AmbientAndDirectional,  // what a full-screen pass is for; local lights get volumes (ch. 03)
};

// Draws one triangle that covers the viewport; the fragment shader does the work.
class FullScreenPass {
 public:
  void draw() const;
 private:
  gl::VertexArray empty_;  // core profile needs a vertex array even without attributes
};

class DeferredLighting {
 public:
  static constexpr GLuint kFirstUnit = 0;  // G-buffer textures on units 0..4

  // Lights `gbuffer` into the framebuffer that is bound (sRGB output: linear values are
  // written). Sky pixels get `background`. Depth test, blending and culling are off.
  void draw(const GBuffer& gbuffer, const ch01::LightBuffer& lights, const glm::vec3& ambient,
            const glm::vec3& background, LightSelection selection = LightSelection::All);
  void reload_shaders();

 private:
  std::map<std::string, ShaderProgram> programs_;  // one per layout
  FullScreenPass quad_;
};

// [buffer-views]
enum class BufferView { Albedo, Normal, Depth, Specular, Exponent, Emissive, Position };
inline const std::vector<std::string> kBufferViews = {"albedo", "normal", "depth", "specular", "exponent", "emissive", "position"};
// [/buffer-views]
bool is_buffer_view(const std::string& name);
BufferView buffer_view(const std::string& name);  // throws Error for an unknown name

// Shows one G-buffer quantity as an image: colours as they are, the normal as
// n * 0.5 + 0.5, depth as log(distance / near) / log(far / near), the exponent as
// log2(n) / 13, the reconstructed position as colour bands 2 m apart. Sky pixels: `background`.
class BufferViewPass {
 public:
  void draw(const GBuffer& gbuffer, BufferView view, const glm::vec3& background);
  void reload_shaders();

 private:
  std::map<std::string, ShaderProgram> programs_;
  FullScreenPass quad_;
};

}  // namespace lp::ch02
