#pragma once
// The scene's lights packed for the shaders (GpuLight in shaders/lighting.glsl) in a shader
// storage buffer, so one draw can loop over any number of them.
#include <vector>

#include <glm/glm.hpp>

#include "common/gl.h"
#include "common/scene.h"

namespace lp::ch01 {

namespace glsl {
using glm::vec4;
#include "chapters/01_forward/shaders/gpu_light.h"  // struct GpuLight, shared with GLSL
}  // namespace glsl
using glsl::GpuLight;
static_assert(sizeof(GpuLight) == 64, "std430: four vec4");

GpuLight pack_light(const Light& light);

// The scene's lights, or `count` lights when count > 0: the scene's first ones and then
// deterministic extra point lights spread over the scene, for "cost as lights grow".
std::vector<Light> lights_for_count(const Scene& scene, int count);

class LightBuffer {
 public:
  static constexpr GLuint kBinding = 0;  // layout(std430, binding = 0) in the shaders
  void upload(const std::vector<Light>& lights);
  void bind() const { glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBinding, buffer_.id()); }
  int count() const { return count_; }

 private:
  gl::Buffer buffer_;
  int count_ = 0;
};

}  // namespace lp::ch01
