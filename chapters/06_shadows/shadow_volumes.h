#pragma once
// Chapter 06's shadow volumes for the sun, built on the CPU: per mesh once, the edge table
// (which triangles share each edge, and in which direction they run along it); per frame,
// for the sun's direction, the volume's triangles in world space as homogeneous positions:
// the caps (w = 1) and the sides extruded to infinity (w = 0), drawn by ShadowStage with
// depth clamp and the z-fail stencil count.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "common/scene.h"

namespace lp::ch06 {

// [adjacency]
// The edge table of one mesh, built once. glTF splits vertices at seams (a new normal or uv is
// a new vertex), so the table welds by position first: two indices whose positions are equal
// bit for bit are one corner. Each edge (two welded corners, smaller first) lists the
// triangles that use it with their direction along it: +1 if the triangle runs from the
// smaller corner to the larger, -1 the other way. A closed manifold mesh has exactly one +1
// and one -1 per edge; an open edge (a floor's border) has one entry; a non-manifold edge
// three or more. The volume below does not need manifold meshes: see [silhouette].
struct MeshAdjacency {
  struct Use { std::uint32_t triangle; int direction; };
  struct Edge { std::uint32_t a, b; std::vector<Use> uses; };  // welded corners, a < b
  std::vector<glm::vec3> corners;                  // welded positions (object space)
  std::vector<std::uint32_t> triangles;            // 3 corners per triangle, the mesh's winding
  std::vector<std::uint8_t> double_sided;          // per triangle: its material is double-sided
  std::vector<Edge> edges;
  std::size_t open_edges = 0, non_manifold_edges = 0;
};
MeshAdjacency build_adjacency(const Scene& scene, const Mesh& mesh);
// [/adjacency]

// [silhouette]
// The sun's volume of one instance, appended to `out` (4 floats a vertex, 3 vertices a
// triangle, world space). A triangle casts if it faces the light (its world normal, from its
// winding, against the light: so mirrored instances work), or, facing away, if its material is
// double-sided or its mesh is not closed (an open edge or a non-manifold one), taken with its
// winding turned towards the light: a one-sided wall stops the light from both sides, for the
// ray tracer and the maps alike (only behind a closed mesh does the side facing the light
// alone cover every point the back faces would). Each casting triangle's volume is a prism:
// the triangle itself (the cap, w = 1), pushed `offset` metres along the light so that it lies
// just behind the surface it came from (the surface is then outside its own volume: no
// self-shadowing from depth rounding), three sides to infinity along the light (w = 0) and a far
// cap that, for a directional light, is a single point (no area: it is left out). The sides of
// two casting triangles sharing an edge run opposite ways and cancel in the stencil count, so
// only each edge's net count is drawn: the sum of the directions of its casting triangles,
// |sum| sides of that orientation. For a closed mesh that is the silhouette: the edges between
// a triangle facing the light and one facing away (sum +-1), every other edge 0. An open edge
// with a casting triangle is always a silhouette; a non-manifold edge gets its net count; so the
// volume is closed for any triangle soup, which z-fail needs.
struct VolumeCounts {
  std::size_t cap_triangles = 0, side_quads = 0;
};
VolumeCounts append_sun_volume(const MeshAdjacency& mesh, const glm::mat4& model, glm::vec3 sun_direction,
                               float offset, std::vector<glm::vec4>& out);
// [/silhouette]

}  // namespace lp::ch06
