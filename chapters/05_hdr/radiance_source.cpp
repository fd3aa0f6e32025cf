#include "chapters/05_hdr/radiance_source.h"

#include <algorithm>
#include <string>

#include "chapters/01_forward/ground_truth.h"
#include "common/error.h"

namespace lp::ch05 {

RadianceTarget::RadianceTarget(int w, int h, GLenum format)
    : width_(w), height_(h), format_(format),
      colour_(gl::make_texture_2d(format, w, h)),
      depth_(gl::make_texture_2d(GL_DEPTH24_STENCIL8, w, h)) {
  glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT0, colour_.id(), 0);
  glNamedFramebufferTexture(fbo_.id(), GL_DEPTH_STENCIL_ATTACHMENT, depth_.id(), 0);
  if (glCheckNamedFramebufferStatus(fbo_.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Error("the radiance framebuffer (" + std::to_string(w) + "x" + std::to_string(h) + ") is incomplete");
}

std::size_t RadianceTarget::bytes() const {
  return std::size_t(width_) * height_ * (gl::bytes_per_texel(format_) + gl::bytes_per_texel(GL_DEPTH24_STENCIL8));
}

void RadianceTarget::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
  glViewport(0, 0, width_, height_);
}

ImageF RadianceTarget::read() const { return read_texture(colour_.id(), width_, height_); }

gl::Texture upload_radiance(const ImageF& image, GLenum format) {
  if (image.channels < 3) throw Error("upload_radiance needs an RGB or RGBA image");
  std::vector<float> rgba(std::size_t(image.width) * image.height * 4, 1.f);
  for (int y = 0; y < image.height; ++y)  // OpenGL's first row is the bottom one
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c)
        rgba[(std::size_t(image.height - 1 - y) * image.width + x) * 4 + c] = image.at(x, y, c);
  gl::Texture t = gl::make_texture_2d(format, image.width, image.height);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(t.id(), 0, 0, 0, image.width, image.height, GL_RGBA, GL_FLOAT, rgba.data());
  return t;
}

ImageF read_texture(GLuint texture, int w, int h) {
  ImageF img = ImageF::blank(w, h, 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(img.data.size() * sizeof(float)), img.data.data());
  flip_vertically(img);
  return img;
}

Scene rescaled_scene(const Scene& scene, float sun, float glow) {
  Scene s = scene;
  for (auto& l : s.lights)
    if (l.type == LightType::Directional) l.intensity *= sun;
  for (auto& m : s.materials) m.emissive *= glow;
  return s;
}

ForwardRadiance::ForwardRadiance(const Scene& scene) : original_(scene) { set_scales(1, 1); }

void ForwardRadiance::set_scales(float sun, float glow) {
  if (sun == sun_ && glow == glow_) return;
  sun_ = sun;
  glow_ = glow;
  if (!scene_) {
    scene_ = std::make_unique<Scene>(rescaled_scene(original_, sun, glow));
    gpu_ = std::make_unique<SceneGpu>(*scene_);
    forward_ = std::make_unique<ch01::ForwardRenderer>(*gpu_);
  } else {
    // The GPU scene reads materials from *scene_ at draw time: rescale them in place.
    for (std::size_t i = 0; i < scene_->materials.size(); ++i)
      scene_->materials[i].emissive = original_.materials[i].emissive * glow;
    for (std::size_t i = 0; i < scene_->lights.size(); ++i)
      scene_->lights[i].intensity = original_.lights[i].intensity * (original_.lights[i].type == LightType::Directional ? sun : 1.f);
  }
  lights_.upload(scene_->lights);
}

void ForwardRadiance::render(const FrameCamera& camera, const RadianceTarget& target) const {
  target.bind();
  glClearColor(ch01::kBackground.r, ch01::kBackground.g, ch01::kBackground.b, 1.f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  forward_->draw(camera, ch01::ForwardMode::PerPixel, lights_);
}

}  // namespace lp::ch05
