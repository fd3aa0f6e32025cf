#include "chapters/01_forward/ground_truth_view.h"

#include "chapters/01_forward/ground_truth.h"

namespace lp::ch01 {

void GroundTruthView::draw(const Frame& f, const std::vector<Light>& lights) {
  if (f.camera.view != last_view_ || f.width != width_ || f.height != height_ || lights.size() != light_count_) {
    Camera camera{.world = glm::inverse(f.camera.view), .yfov = f.camera.yfov, .znear = f.camera.znear, .zfar = f.camera.zfar};
    GroundTruth gt = render_ground_truth(scene_, camera, f.width, f.height, lights);
    flip_vertically(gt.radiance);  // OpenGL's first row is the bottom one
    texture_ = gl::make_texture_2d(GL_RGB32F, f.width, f.height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(texture_.id(), 0, 0, 0, f.width, f.height, GL_RGB, GL_FLOAT, gt.radiance.data.data());
    fbo_ = gl::Framebuffer();
    glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT0, texture_.id(), 0);
    last_view_ = f.camera.view;
    width_ = f.width;
    height_ = f.height;
    light_count_ = lights.size();
  }
  // With GL_FRAMEBUFFER_SRGB on, the blit encodes the linear floats to sRGB.
  glBlitNamedFramebuffer(fbo_.id(), f.target, 0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

}  // namespace lp::ch01
