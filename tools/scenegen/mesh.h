// Procedural triangle meshes for scenegen. Conventions (what the glTF writer and the book's
// loader expect):
//   - counter-clockwise front faces, outward normals;
//   - glTF UV space: (0,0) is the top-left of the image, v grows downwards;
//   - tangent.xyz points along +u, and bitangent = cross(normal, tangent.xyz) * tangent.w
//     points along -v (image "up"), as glTF/MikkTSpace define it. All generators here
//     produce w = +1.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace scenegen {

struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;   // empty: no NORMAL attribute
  std::vector<glm::vec2> uvs;       // empty: no TEXCOORD_0
  std::vector<glm::vec4> tangents;  // empty: no TANGENT
  std::vector<uint32_t> indices;    // empty: non-indexed triangle list

  size_t vertex_count() const { return positions.size(); }
  // Appends `other` transformed by `xf` (rotation + translation, optionally uniform scale).
  void append(const Mesh& other, const glm::mat4& xf = glm::mat4(1.0f));
};

// Rotation whose columns are (x_axis, normal, cross(x_axis, normal)): maps the local XZ plane
// with +Y normal onto a plane with the given normal, local +X going along x_axis. Both must be
// unit length and perpendicular. With x_axis chosen "to the right when looking at the face",
// local +Z (= texture v) points "down" and textures appear upright.
glm::mat3 face_frame(const glm::vec3& normal, const glm::vec3& x_axis);

// UV sphere centred at the origin. `segments` around the Y axis, `rings` from pole to pole.
// u = longitude (0 at +Z, growing towards +X), v = 0 at the north (+Y) pole.
Mesh make_uv_sphere(float radius, int segments, int rings);

// Rectangle in the XZ plane, normal +Y, centred at the origin, sx along X and sz along Z,
// divided into div_x * div_z quads; u = uv_scale.x * (x / sx + 0.5), v likewise along Z.
Mesh make_rect(float sx, float sz, int div_x = 1, int div_z = 1, glm::vec2 uv_scale = glm::vec2(1.0f));

// Axis-aligned box centred at the origin; each face a rect with `uv_per_metre` texture repeats
// per metre, upright on the side faces.
Mesh make_box(const glm::vec3& size, float uv_per_metre = 1.0f);

// Open cylinder (no caps) around +Y from y = 0 to y = height. u around, v down the height.
Mesh make_cylinder(float radius, float height, int segments, glm::vec2 uv_scale = glm::vec2(1.0f));

// Half torus: the tube's centre line is the upper half circle of radius `major` in the XY plane
// (from +X over +Y to -X), tube radius `minor`. Its two open ends lie flat in the plane y = 0.
Mesh make_half_torus(float major, float minor, int major_segments, int minor_segments,
                     glm::vec2 uv_scale = glm::vec2(1.0f));

// Per-vertex tangents from positions, normals and UVs (Lengyel's method, glTF handedness).
// Used to check the analytic tangents of the generators above.
std::vector<glm::vec4> compute_tangents(const Mesh& mesh);

}  // namespace scenegen
