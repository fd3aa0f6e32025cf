#pragma once
// The shapes a light is drawn with: a subdivided icosahedron for a point light and a cone
// for a spot light. Both are closed, convex and wound counter-clockwise seen from outside,
// and both enclose the shape they stand for: a polygonal sphere drawn through the points of
// the true sphere would cut the light short between its vertices, so we push it out until
// every face lies on or outside the sphere.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace lp::ch03 {

struct VolumeMesh {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;  // triangles, counter-clockwise seen from outside

  std::size_t triangle_count() const { return indices.size() / 3; }
  // Signed distance of p from the plane of triangle t (positive outside).
  float plane_distance(std::size_t t, const glm::vec3& p) const;
  // Inside or on the surface: p is behind (or within `margin` of) every face's plane.
  bool contains(const glm::vec3& p, float margin = 0.f) const;
  // The mesh's volume (divergence theorem over its triangles).
  double volume() const;
};

// An icosahedron whose triangles are split into four `subdivisions` times, its vertices
// pushed onto a sphere and the whole scaled so that it circumscribes the unit sphere: the
// closest face plane touches it. 20 * 4^s triangles.
VolumeMesh icosphere(int subdivisions);
// The scale that was applied: the distance from the centre to the vertices.
float icosphere_circumradius(int subdivisions);

// A cone with its apex at the origin, its axis along +Z and its base at z = 1: a regular
// `sides`-gon circumscribing the unit circle (so the circular cone of half-angle 45 degrees
// fits inside), closed by a fan. Scaled per light to height r and base radius r * tan(angle).
VolumeMesh cone(int sides);

// [cone-or-sphere]
// A spot light is drawn with the cone while the cone is the smaller shape; past about 63
// degrees (tan^2 = 4) a sphere of the same radius encloses less, and from 90 degrees on a
// cone cannot enclose the light at all.
// The volumes are those of the unit meshes (cone of height 1 with base radius 1, sphere of
// radius 1); the cone's grows with tan^2 of the angle.
bool spot_uses_cone(float outer_cone_angle, double unit_cone_volume, double unit_sphere_volume);
// [/cone-or-sphere]

// The two unit meshes a renderer draws every light with, and their volumes.
struct VolumeShapes {
  int sphere_subdivisions = 2, cone_sides = 16;
  VolumeMesh sphere, cone;
  double sphere_volume = 0, cone_volume = 0;  // of the unit meshes
};
VolumeShapes make_volume_shapes(int sphere_subdivisions = 2, int cone_sides = 16);

}  // namespace lp::ch03
