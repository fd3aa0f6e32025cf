#pragma once
// Chapter 07's inner corner: the closed-form AO of a 90-degree dihedral for rays of length R,
// and the Cornell box's view of one (its floor meeting its back wall) that the hard-case test
// (tests/unit/test_07_ssao_hard_gl.cpp) and the sweep's corner rows hold each method to.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "common/camera.h"
#include "common/raytrace.h"
#include "common/scene.h"

namespace lp::ch07 {

// [dihedral]
// The AO of a point at distance x from the other face of an inner 90-degree corner (two
// half-planes, each extending beyond R), rays of length R: a cosine-weighted direction is a
// uniform point of the unit disk lifted onto the hemisphere (Malley), and the ray hits the
// other face within R exactly when its component toward that face exceeds h = x / R. Those
// directions are the disk's circular segment beyond the chord at h, of area
// acos(h) - h sqrt(1 - h^2), out of the disk's pi:
//   A(h) = 1 - (acos(h) - h sqrt(1 - h^2)) / pi,  h = x / R <= 1;  A = 1 beyond R.
// At the crease A = 1/2 (the face hides half the cosine lobe: the unlimited-radius value for
// every x); at h = 1 it is 1.
inline double dihedral_ao(double h) {
  if (h >= 1.0) return 1.0;
  h = std::max(h, 0.0);
  return 1.0 - (std::acos(h) - h * std::sqrt(1.0 - h * h)) / 3.14159265358979;
}
// [/dihedral]

// The corner view: the crease of the Cornell box's floor (y = 0) and back wall (z = -1)
// between the tall box and the right wall, seen from in front and above, R = 0.25. Only the
// crease's other face lies within R of the pixels used: x in [0.25, 0.7] keeps them more than R
// from the tall box (its largest x is -0.045) and from the right wall (x = 1); the short box
// ends at z = -0.055, more than R in front of the floor's z <= -0.72 that the view shows. From
// 1.8 m, R projects to at most 40 pixels there, under the disk's and GTAO's screen-radius clamp
// (0.25 H = 45 pixels at H = 180): they reach all of R.
inline constexpr float kCornerRadius = 0.25f;
inline const glm::vec3 kCornerEye{0.48f, 1.2f, 0.4f};
inline FrameCamera corner_camera(float aspect) {
  Camera c;
  c.world = glm::inverse(glm::lookAt(kCornerEye, glm::vec3(0.48f, 0.0f, -1.0f), glm::vec3(0, 1, 0)));
  c.yfov = 0.6864f, c.znear = 0.01f, c.zfar = 20.f;
  return frame_camera(c, aspect);
}

struct CornerPixel {
  int x, y;
  double h;          // distance to the other face, over R
  double radius_px;  // R projected at the pixel's view depth, for an image `height` rows high
};
// The floor and back-wall pixels of the view with x in [0.25, 0.7] (rows top to bottom).
inline std::vector<CornerPixel> corner_pixels(const Scene& scene, const RayScene& rays, const FrameCamera& cam,
                                              int width, int height) {
  const auto hits = primary_hits(rays, cam, width, height);
  std::vector<CornerPixel> out;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const auto& h = hits[std::size_t(y) * width + x];
      if (!h || h->position.x < 0.25f || h->position.x > 0.7f) continue;
      const std::string& name = scene.instances[std::size_t(h->instance)].name;
      const double z = -(cam.view * glm::vec4(h->position, 1.f)).z;
      const double radius_px = kCornerRadius * cam.projection[1][1] * 0.5 * height / z;
      if (name == "floor") out.push_back({x, y, (h->position.z + 1.0) / kCornerRadius, radius_px});
      else if (name == "back_wall") out.push_back({x, y, h->position.y / kCornerRadius, radius_px});
    }
  return out;
}

}  // namespace lp::ch07
