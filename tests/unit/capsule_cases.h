#pragma once
// The tubes' binning's hard case, for chapter 09's unit test (cluster_grid.h's
// capsule_meets_box) and its GLSL twin (grid.glsl's): a capsule that touches a cluster's box by
// less than float rounding. The camera stands 150 m from the world's origin (the size of
// chapter 10's street), where a coordinate's unit in the last place is 15 um, more than the old
// padding (1e-5 of a radius of a few cm, plus 1 um). Each tube runs across a face of a cluster's
// box at exactly the radius from it: the exact distance is computed in double from the float
// world-space ends the GPU holds, and the radius is at least that and at least what
// neon_light()'s float distance from the face's point gives (a pixel there is lit).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "chapters/09_clustered/cluster_grid.h"

namespace lp::test {

// The grid tests' camera: at the origin, looking down -z, 16:9, near 0.1, far 100.
inline FrameCamera grid_test_camera() {
  FrameCamera c;
  c.yfov = 0.8f;
  c.aspect = 16.f / 9.f;
  c.znear = 0.1f;
  c.zfar = 100.f;
  c.projection = glm::perspective(c.yfov, c.aspect, c.znear, c.zfar);
  return c;
}

// The exact distance from the segment a-b to the box, in double: convex along the segment, so
// minimised by ternary search.
inline double segment_box_distance(const glm::dvec3& a, const glm::dvec3& b, const ch09::Box& box) {
  auto at = [&](double t) {
    const glm::dvec3 p = a + t * (b - a);
    return glm::length(p - glm::clamp(p, glm::dvec3(box.lo), glm::dvec3(box.hi)));
  };
  double lo = 0, hi = 1;
  for (int j = 0; j < 200; ++j) {
    const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    if (at(m1) <= at(m2))
      hi = m2;
    else
      lo = m1;
  }
  return std::min({at(0), at(1), at(0.5 * (lo + hi))});
}

struct CapsuleCase {
  glm::vec3 a, b;          // the tube's ends in view space, as the GPU's float transform gives them
  float radius = 0;        // its cut
  float eye_distance = 0;  // the camera's distance from the world's origin
  ch09::Box box;           // the cluster's box
  double exact = 0;        // the exact distance from the segment to the box
  float shaded = 0;        // neon_light()'s float distance from the face's point to the segment
};

inline std::vector<CapsuleCase> touching_capsules(FrameCamera c, const ch09::Grid& grid, int count) {
  const glm::dvec3 eye(120.0, 1.7, -90.0), target(125.0, 1.2, -60.0);
  const glm::dmat4 view_d = glm::lookAt(eye, target, glm::dvec3(0, 1, 0));
  const glm::dmat4 world_d = glm::inverse(view_d);
  c.view = glm::mat4(view_d);
  std::uint32_t state = 777u;
  auto uniform = [&](double lo, double hi) {
    state = state * 1664525u + 1013904223u;
    return lo + (hi - lo) * double(state >> 8) / double(1u << 24);
  };
  std::vector<CapsuleCase> cases;
  for (int i = 0; i < count; ++i) {
    CapsuleCase k;
    k.eye_distance = float(glm::length(eye));
    k.box = ch09::cluster_box(c, grid, int(uniform(0, grid.tiles_x)), int(uniform(0, grid.tiles_y)),
                              int(uniform(grid.slices / 6, grid.slices)));
    const ch09::Box& box = k.box;
    const int axis = i % 3;
    const double side = (i / 3) % 2 ? 1.0 : -1.0, r = uniform(0.02, 0.5);
    // A point of the face, the segment r beyond it, running parallel to the face.
    glm::dvec3 q;
    for (int j = 0; j < 3; ++j) q[j] = uniform(box.lo[j], box.hi[j]);
    q[axis] = side > 0 ? box.hi[axis] : box.lo[axis];
    glm::dvec3 along(0.0), mid = q;
    along[(axis + 1) % 3] = uniform(-1, 1);
    along[(axis + 2) % 3] = uniform(-1, 1);
    mid[axis] += side * r;
    const double half = uniform(0.05, 1.0);
    const glm::vec3 wa(world_d * glm::dvec4(mid - half * along, 1.0)), wb(world_d * glm::dvec4(mid + half * along, 1.0));
    const glm::dvec3 ea(view_d * glm::dvec4(glm::dvec3(wa), 1.0)), eb(view_d * glm::dvec4(glm::dvec3(wb), 1.0));
    k.exact = segment_box_distance(ea, eb, box);
    const glm::vec3 x(world_d * glm::dvec4(q, 1.0)), ab = wb - wa;
    const float t = glm::clamp(glm::dot(x - wa, ab) / glm::dot(ab, ab), 0.f, 1.f);
    k.shaded = glm::length(x - glm::mix(wa, wb, t));
    k.radius = std::max(float(k.exact), k.shaded);
    if (double(k.radius) < k.exact) k.radius = std::nextafter(k.radius, 1e30f);  // the cut reaches the box
    k.a = glm::vec3(c.view * glm::vec4(wa, 1.f));
    k.b = glm::vec3(c.view * glm::vec4(wb, 1.f));
    cases.push_back(k);
  }
  return cases;
}

}  // namespace lp::test
