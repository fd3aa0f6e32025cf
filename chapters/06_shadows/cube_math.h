#pragma once
// [cube-math]
// A point light's shadows in a cube map: six square perspective maps of 90 degrees around the
// light, one per axis direction, each storing the linear distance from the light to the nearest
// surface (window depth = distance / far). A lookup is a direction from the light; OpenGL picks
// the face by the direction's largest component (the major axis) and the texel from the other
// two over it (the specification's cube map table, cube_face_coords below). The depth pass draws
// each face through cube_face_view_projection, which must put a direction on the texel the
// sampler reads: the two are the same map, and the unit tests hold them to each other.
#include <array>

#include <glm/glm.hpp>

namespace lp::ch06 {

inline constexpr int kMaxPointShadows = 8;     // point lights with a cube map in one frame
inline constexpr float kCubeNear = 0.05f;      // metres: the faces' near plane

// Faces in OpenGL's order (GL_TEXTURE_CUBE_MAP_POSITIVE_X + face, the layer's face index).
enum class CubeFace { PositiveX, NegativeX, PositiveY, NegativeY, PositiveZ, NegativeZ };
struct CubeCoords {
  CubeFace face = CubeFace::PositiveX;
  glm::vec2 st{0.5f};  // the texel position on the face, [0, 1]^2 (s to the right, t up the rows)
};
// The face and (s, t) that a cube map lookup with `direction` (not zero) reads.
CubeCoords cube_face_coords(glm::vec3 direction);
// The view (from `position`) and projection (90 degrees, square, near kCubeNear, `far`) of a
// face, as the depth pass draws it: clip-space x, y over w are 2s - 1 and 2t - 1 of the
// direction's cube_face_coords.
glm::mat4 cube_face_view(glm::vec3 position, CubeFace face);
glm::mat4 cube_face_view_projection(glm::vec3 position, CubeFace face, float far);
// A texel's width at `distance` from the light on a face of `size` texels: 2 d / N at the
// face's centre (a face spans tan 45 = 1 each side), less towards its edges; the bias and the
// normal offset are in units of it, as the spot's (shadow_math.h [spot-frustum]).
inline float cube_texel_world(float distance, int size) { return 2.f * distance / float(size); }
// The far plane of a point light's faces: the farthest corner of the scene's bounds, or its
// range when that is nearer (range 0: unbounded).
float cube_far(glm::vec3 position, float range, glm::vec3 scene_min, glm::vec3 scene_max);

}  // namespace lp::ch06
// [/cube-math]
