#pragma once
// Scenes whose geometry is known to the pixel, for GL tests: quads facing an orthographic camera
// whose world units are pixels (x 0..w, y 0..h, y up), seen from 1000 units away. An edge placed
// at x = k + 0.5 runs through the centres of column k, one at an integer x between two columns.
#include <string>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "common/camera.h"
#include "common/scene.h"

namespace lp::test {

// A unit quad in the plane z = 0 (x, y in 0..1, facing +z) placed by `model`.
inline void add_unit_quad(Scene& s, int material, const glm::mat4& model) {
  const auto first_vertex = static_cast<std::uint32_t>(s.vertices.size());
  for (glm::vec2 c : {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)})
    s.vertices.push_back(Vertex{glm::vec3(c.x, c.y, 0), glm::vec3(0, 0, 1), c, glm::vec4(1, 0, 0, 1)});
  const auto first_index = static_cast<std::uint32_t>(s.indices.size());
  for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) s.indices.push_back(first_vertex + i);
  s.meshes.push_back(Mesh{"quad", {Primitive{first_index, 6, material}}});
  s.instances.push_back(Instance{"quad " + std::to_string(s.instances.size()), int(s.meshes.size()) - 1, model, {}});
}

// The orthographic camera whose world units are the pixels of a w x h target.
inline FrameCamera pixel_camera(int w, int h) {
  FrameCamera c;
  c.position = glm::vec3(0, 0, 1000);
  c.view = glm::lookAt(c.position, glm::vec3(0, 0, 0), glm::vec3(0, 1, 0));
  c.projection = glm::ortho(0.f, float(w), 0.f, float(h), 900.f, 1100.f);
  c.znear = 900, c.zfar = 1100, c.aspect = float(w) / float(h);
  return c;
}

}  // namespace lp::test
