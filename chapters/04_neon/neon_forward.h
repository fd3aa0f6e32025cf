#pragma once
// A forward renderer for the neon tubes: every object is drawn once, and each fragment is lit
// by chapter 01's lights and by every tube with the selected method (shaders/neon.glsl).
// It is the chapter's yardstick: neon_volumes.h draws the same tubes as capsule volumes over
// chapter 02's G-buffer (the default path), and the tests hold the two images together.
// NeonTubes serves both: the packed instances and the unit capsule.
#include <vector>

#include "chapters/01_forward/light_buffer.h"
#include "chapters/04_neon/capsule.h"
#include "chapters/04_neon/neon.h"
#include "common/camera.h"
#include "common/gl.h"
#include "common/scene_gpu.h"
#include "common/shader.h"

namespace lp::ch04 {

// What the fragment shader writes: the whole image, or one neon term alone (for measuring).
enum class Term { All = 0, Diffuse = 1, Specular = 2 };

struct NeonDraw {
  Method method = Method::Improved;
  int samples = 256;  // ground truth: samples per tube; points: point lights per tube
  Term term = Term::All;
};

// The tubes on the GPU: packed (capsule.h) in one buffer that is both the shaders' storage
// buffer and the per-instance vertex stream of the capsule mesh.
class NeonTubes {
 public:
  static constexpr GLuint kBinding = 1;  // layout(std430, binding = 1) in the shaders
  NeonTubes();
  void upload(const std::vector<NeonLight>& tubes, float threshold = kNeonCut);
  void bind() const { glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBinding, buffer_.id()); }
  int count() const { return count_; }
  const std::vector<NeonGpu>& packed() const { return packed_; }
  // Draws every tube's capsule, instanced (the program sets the rest).
  void draw_capsules() const;
  // Draws tube `index`'s capsule alone: the same instanced draw, one instance from `index`.
  void draw_capsule(int index) const;

 private:
  gl::VertexArray vao_;
  gl::Buffer vertices_, indices_, buffer_;
  GLsizei index_count_ = 0;
  int count_ = 0;
  std::vector<NeonGpu> packed_;
};

class NeonForward {
 public:
  explicit NeonForward(const SceneGpu& scene);
  void reload_shaders();
  // The scene lit by `lights` (chapter 01) and the tubes, then the glowing glass of the tubes.
  void draw(const FrameCamera& camera, const NeonDraw& how, const ch01::LightBuffer& lights,
            const NeonTubes& tubes) const;
  // The glowing glass alone, depth-tested against the bound framebuffer's depth.
  void draw_glass(const FrameCamera& camera, const NeonTubes& tubes) const;

 private:
  const SceneGpu& scene_;
  ShaderProgram lit_, glass_;
};

}  // namespace lp::ch04
