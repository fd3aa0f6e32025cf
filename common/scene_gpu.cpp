#include "common/scene_gpu.h"

#include <cmath>
#include <cstddef>
#include <cstring>
#include <iostream>

#include <glm/glm.hpp>

namespace lp {
namespace {

gl::Texture upload(const ImageRGBA8& img, bool srgb) {
  int levels = 1 + static_cast<int>(std::floor(std::log2(std::max(img.width, img.height))));
  gl::Texture t = gl::make_texture_2d(srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, img.width, img.height, levels);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(t.id(), 0, 0, 0, img.width, img.height, GL_RGBA, GL_UNSIGNED_BYTE, img.pixels.data());
  glGenerateTextureMipmap(t.id());
  glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(t.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(t.id(), GL_TEXTURE_WRAP_T, GL_REPEAT);
  return t;
}

ImageRGBA8 solid(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  ImageRGBA8 img;
  img.width = img.height = 1;
  img.pixels = {r, g, b, 255};
  return img;
}

// The magenta checker (colour) or flat normal (linear) that stands in for a texture GL cannot hold.
ImageRGBA8 stand_in(bool srgb) {
  ImageRGBA8 img = ImageRGBA8::blank(8, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      glm::u8vec4 c = !srgb ? glm::u8vec4(128, 128, 255, 255) : ((x ^ y) & 1) ? glm::u8vec4(255, 0, 255, 255) : glm::u8vec4(32, 32, 32, 255);
      std::memcpy(img.at(x, y), &c, 4);
    }
  return img;
}

}  // namespace

SceneGpu::SceneGpu(const Scene& scene)
    : scene_(scene),
      vertices_(gl::make_buffer(scene.vertices.data(), scene.vertices.size() * sizeof(Vertex))),
      indices_(gl::make_buffer(scene.indices.data(), scene.indices.size() * sizeof(std::uint32_t))),
      white_(upload(solid(255, 255, 255), true)),
      flat_normal_(upload(solid(128, 128, 255), false)) {
  GLuint vao = vao_.id();
  glVertexArrayVertexBuffer(vao, 0, vertices_.id(), 0, sizeof(Vertex));
  glVertexArrayElementBuffer(vao, indices_.id());
  auto attribute = [vao](GLuint location, int size, std::size_t offset) {
    glEnableVertexArrayAttrib(vao, location);
    glVertexArrayAttribFormat(vao, location, size, GL_FLOAT, GL_FALSE, static_cast<GLuint>(offset));
    glVertexArrayAttribBinding(vao, location, 0);
  };
  attribute(kPosition, 3, offsetof(Vertex, position));
  attribute(kNormal, 3, offsetof(Vertex, normal));
  attribute(kUv, 2, offsetof(Vertex, uv));
  attribute(kTangent, 4, offsetof(Vertex, tangent));
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  for (const auto& t : scene.textures) {
    if (t.image.width > max_size || t.image.height > max_size) {
      warnings_.push_back("texture '" + t.name + "' is " + std::to_string(t.image.width) + "x" + std::to_string(t.image.height) +
                          ", larger than this GL allows (GL_MAX_TEXTURE_SIZE " + std::to_string(max_size) + "): using a fallback " +
                          (t.srgb ? "checker" : "flat normal map"));
      std::cerr << "warning: " << warnings_.back() << '\n';
      textures_.push_back(upload(stand_in(t.srgb), t.srgb));
      continue;
    }
    textures_.push_back(upload(t.image, t.srgb));
  }
}

// [winding]
// Two things of glTF that a pass's culling state must follow per draw, so every pass that
// draws the scene gets them without knowing: an instance whose transform mirrors (negative
// determinant) turns its triangles' winding around, so its front faces are the other
// winding; and a doubleSided material is drawn with culling off (its shaders flip the normal
// of back faces: chapter 01's surface_normal()). The pass's own state is restored after.
namespace {
class GltfFaceRules {
 public:
  GltfFaceRules() : culling_(glIsEnabled(GL_CULL_FACE)) { glGetIntegerv(GL_FRONT_FACE, &front_); }
  ~GltfFaceRules() {  // GL calls: nothing here throws
    glFrontFace(GLenum(front_));
    if (culling_) glEnable(GL_CULL_FACE);
  }
  GltfFaceRules(const GltfFaceRules&) = delete;
  GltfFaceRules& operator=(const GltfFaceRules&) = delete;
  void instance(const Instance& inst) const {
    const bool mirrored = glm::determinant(glm::mat3(inst.model)) < 0;
    glFrontFace(mirrored ? (front_ == GL_CCW ? GL_CW : GL_CCW) : GLenum(front_));
  }
  void material(const Material& m) const {
    if (culling_) m.double_sided ? glDisable(GL_CULL_FACE) : glEnable(GL_CULL_FACE);
  }

 private:
  bool culling_;
  GLint front_ = GL_CCW;
};

void draw_elements(const Primitive& p) {
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(p.index_count), GL_UNSIGNED_INT,
                 reinterpret_cast<const void*>(std::uintptr_t(p.first_index) * sizeof(std::uint32_t)));
}
}  // namespace

void SceneGpu::draw(const DrawCallback& before_each_primitive, Primitives which) const {
  glBindVertexArray(vao_.id());
  const GltfFaceRules rules;
  for (const auto& inst : scene_.instances) {
    rules.instance(inst);
    for (const auto& p : scene_.meshes[inst.mesh].primitives) {
      const Material& material = scene_.materials[p.material];
      if ((which == Primitives::Opaque && material.blend) || (which == Primitives::Blended && !material.blend)) continue;
      rules.material(material);
      before_each_primitive(inst, material);
      draw_elements(p);
    }
  }
}
// [/winding]

void SceneGpu::draw_primitive(std::size_t instance, std::size_t primitive) const {
  const Instance& inst = scene_.instances.at(instance);
  const Primitive& p = scene_.meshes.at(inst.mesh).primitives.at(primitive);
  glBindVertexArray(vao_.id());
  const GltfFaceRules rules;  // the same two rules as draw(), for one primitive
  rules.instance(inst);
  rules.material(scene_.materials.at(p.material));
  draw_elements(p);
}

std::size_t SceneGpu::triangle_count() const {
  std::size_t n = 0;
  for (const auto& inst : scene_.instances)
    for (const auto& p : scene_.meshes[inst.mesh].primitives) n += p.index_count / 3;
  return n;
}

}  // namespace lp
