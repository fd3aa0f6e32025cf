#include "chapters/06_shadows/cube_math.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace lp::ch06 {

// [cube-face-cpp]
CubeCoords cube_face_coords(glm::vec3 d) {
  // OpenGL 4.5's table 8.19: the major axis and the two coordinates (sc, tc) taken across it.
  const glm::vec3 a = glm::abs(d);
  float sc, tc, ma;
  CubeCoords c;
  if (a.x >= a.y && a.x >= a.z) {
    c.face = d.x >= 0.f ? CubeFace::PositiveX : CubeFace::NegativeX;
    sc = d.x >= 0.f ? -d.z : d.z, tc = -d.y, ma = a.x;
  } else if (a.y >= a.z) {
    c.face = d.y >= 0.f ? CubeFace::PositiveY : CubeFace::NegativeY;
    sc = d.x, tc = d.y >= 0.f ? d.z : -d.z, ma = a.y;
  } else {
    c.face = d.z >= 0.f ? CubeFace::PositiveZ : CubeFace::NegativeZ;
    sc = d.z >= 0.f ? d.x : -d.x, tc = -d.y, ma = a.z;
  }
  c.st = 0.5f * (glm::vec2(sc, tc) / ma + 1.f);
  return c;
}

glm::mat4 cube_face_view(glm::vec3 position, CubeFace face) {
  // Looking down the face's axis; the up vector makes the view's x and y the table's sc and tc.
  static const glm::vec3 axis[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  static const glm::vec3 up[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
  const int i = int(face);
  return glm::lookAt(position, position + axis[i], up[i]);
}
// [/cube-face-cpp]

glm::mat4 cube_face_view_projection(glm::vec3 position, CubeFace face, float far) {
  return glm::perspective(glm::radians(90.f), 1.f, kCubeNear, far) * cube_face_view(position, face);
}

float cube_far(glm::vec3 position, float range, glm::vec3 scene_min, glm::vec3 scene_max) {
  float far = 0.f;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 c(i & 1 ? scene_max.x : scene_min.x, i & 2 ? scene_max.y : scene_min.y, i & 4 ? scene_max.z : scene_min.z);
    far = std::max(far, glm::distance(c, position));
  }
  if (range > 0.f) far = std::min(far, range);
  return std::max(far, 2.f * kCubeNear);
}

}  // namespace lp::ch06
