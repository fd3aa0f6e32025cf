#pragma once
// The scene's meshes and textures on the GPU: one vertex array for everything, one texture
// per (image, colour space). Drawing is a loop over instances; the caller sets the
// per-draw state (matrices, material) in a callback, so each chapter decides what it needs.
#include <functional>
#include <string>
#include <vector>

#include "common/gl.h"
#include "common/scene.h"

namespace lp {

class SceneGpu {
 public:
  explicit SceneGpu(const Scene& scene);

  // Vertex attribute locations every chapter's vertex shader uses.
  static constexpr GLuint kPosition = 0, kNormal = 1, kUv = 2, kTangent = 3;

  const Scene& scene() const { return scene_; }
  // The texture for Scene::textures[index], or a white / flat-normal texture for -1.
  GLuint base_color_texture(int index) const { return index < 0 ? white_.id() : textures_[index].id(); }
  GLuint normal_texture(int index) const { return index < 0 ? flat_normal_.id() : textures_[index].id(); }
  // White for -1, so emissive * texel is the emissive factor alone.
  GLuint emissive_texture(int index) const { return base_color_texture(index); }
  // Textures this GL cannot hold (larger than GL_MAX_TEXTURE_SIZE): each replaced by the
  // fallback, with a message naming the image (also printed when the scene is uploaded).
  const std::vector<std::string>& warnings() const { return warnings_; }

  using DrawCallback = std::function<void(const Instance&, const Material&)>;
  // Which primitives draw() draws, by their material's alphaMode: all, the opaque ones (the
  // G-buffer's), or the blended ones (chapter 10's glass).
  enum class Primitives { All, Opaque, Blended };
  // Binds the vertex array and draws every primitive of every instance (of that kind).
  void draw(const DrawCallback& before_each_primitive, Primitives which = Primitives::All) const;
  // Binds the vertex array and draws one primitive of one instance (chapter 10 sorts them).
  void draw_primitive(std::size_t instance, std::size_t primitive) const;
  // Triangles drawn by one draw() call (for the cost report).
  std::size_t triangle_count() const;

 private:
  const Scene& scene_;
  gl::VertexArray vao_;
  gl::Buffer vertices_, indices_;
  std::vector<gl::Texture> textures_;
  gl::Texture white_, flat_normal_;
  std::vector<std::string> warnings_;
};

}  // namespace lp
