#pragma once
// Shows the CPU ground truth in the program's output (mode "ground-truth"): rendered when
// the camera or size changes, uploaded as a float texture and blitted into the sRGB target.
#include <vector>

#include "common/app.h"
#include "common/gl.h"

namespace lp::ch01 {

class GroundTruthView {
 public:
  explicit GroundTruthView(const Scene& scene) : scene_(scene) {}
  void draw(const Frame& frame, const std::vector<Light>& lights);

 private:
  const Scene& scene_;
  gl::Texture texture_{GL_TEXTURE_2D};
  gl::Framebuffer fbo_;
  glm::mat4 last_view_{0};
  int width_ = 0, height_ = 0;
  std::size_t light_count_ = 0;
};

}  // namespace lp::ch01
