#include "chapters/04_neon/neon_forward.h"
#include "chapters/01_forward/material.h"

#include <cstddef>

#include "chapters/01_forward/blinn_phong.h"

namespace lp::ch04 {

NeonTubes::NeonTubes() {
  CapsuleMesh mesh = make_capsule(48, 12);
  vertices_ = gl::make_buffer(mesh.positions.data(), mesh.positions.size() * sizeof(glm::vec3));
  indices_ = gl::make_buffer(mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t));
  index_count_ = static_cast<GLsizei>(mesh.indices.size());
  GLuint vao = vao_.id();
  glVertexArrayVertexBuffer(vao, 0, vertices_.id(), 0, sizeof(glm::vec3));
  glVertexArrayElementBuffer(vao, indices_.id());
  glEnableVertexArrayAttrib(vao, 0);
  glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao, 0, 0);
  // [instance-attributes]
  // Binding 1: one NeonGpu per instance. The four rows of M, the barn doors and the extras
  // are attributes 4..9 (a mat4 attribute takes four locations, one vec4 row each).
  glVertexArrayBindingDivisor(vao, 1, 1);
  for (GLuint i = 0; i < 6; ++i) {
    glEnableVertexArrayAttrib(vao, 4 + i);
    glVertexArrayAttribFormat(vao, 4 + i, 4, GL_FLOAT, GL_FALSE, static_cast<GLuint>(i * sizeof(glm::vec4)));
    glVertexArrayAttribBinding(vao, 4 + i, 1);
  }
  // [/instance-attributes]
}

void NeonTubes::upload(const std::vector<NeonLight>& tubes, float threshold) {
  packed_.clear();
  for (const auto& t : tubes) packed_.push_back(pack_neon(t, volume_radius(t, threshold)));
  buffer_ = gl::make_buffer(packed_.data(), packed_.size() * sizeof(NeonGpu));
  count_ = static_cast<int>(packed_.size());
  glVertexArrayVertexBuffer(vao_.id(), 1, buffer_.id(), 0, sizeof(NeonGpu));
}

void NeonTubes::draw_capsules() const {
  if (count_ == 0) return;
  glBindVertexArray(vao_.id());
  glDrawElementsInstanced(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr, count_);
}

void NeonTubes::draw_capsule(int index) const {
  if (index < 0 || index >= count_) return;
  glBindVertexArray(vao_.id());
  glDrawElementsInstancedBaseInstance(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr, 1, static_cast<GLuint>(index));
}

NeonForward::NeonForward(const SceneGpu& scene)
    : scene_(scene),
      lit_({{GL_VERTEX_SHADER, "01_forward/shaders/forward.vert"}, {GL_FRAGMENT_SHADER, "04_neon/shaders/neon_forward.frag"}}),
      glass_({{GL_VERTEX_SHADER, "04_neon/shaders/capsule.vert"}, {GL_FRAGMENT_SHADER, "04_neon/shaders/glass.frag"}}) {}

void NeonForward::reload_shaders() {
  lit_.reload();
  glass_.reload();
}

void NeonForward::draw(const FrameCamera& camera, const NeonDraw& how, const ch01::LightBuffer& lights,
                       const NeonTubes& tubes) const {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glEnable(GL_CULL_FACE);
  lights.bind();
  tubes.bind();
  lit_.use();
  lit_.set("u_view_projection", camera.view_projection());
  lit_.set("u_eye", camera.position);
  lit_.set("u_ambient", scene_.scene().ambient);
  lit_.set("u_light_count", lights.count());
  lit_.set("u_neon_count", tubes.count());
  lit_.set("u_method", static_cast<int>(how.method));
  lit_.set("u_samples", how.samples);
  lit_.set("u_term", static_cast<int>(how.term));
  scene_.draw([&](const Instance& inst, const Material& m) {
    ch01::set_surface(lit_, scene_, inst, m);  // chapter 01's material.h
  });
  if (how.term != Term::All) return;  // the glass is not part of the light being measured
  draw_glass(camera, tubes);
}

void NeonForward::draw_glass(const FrameCamera& camera, const NeonTubes& tubes) const {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glEnable(GL_CULL_FACE);
  glass_.use();
  glass_.set("u_view_projection", camera.view_projection());
  glass_.set("u_glass", 1);
  tubes.draw_capsules();
  glDisable(GL_CULL_FACE);
}

}  // namespace lp::ch04
