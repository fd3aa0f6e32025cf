#pragma once
// Hard cases of chapter 01's lighting model, shared by the C++ tests (test_lighting.cpp: what
// blinn_phong.h must give) and the GLSL tests (test_forward_gl.cpp: lighting.glsl must give
// the same). Each case is a case because a plausible bug breaks it.
#include <cmath>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "common/scene.h"

namespace lp::test {

struct LightingCase {
  std::string name;
  Light light;
  glm::vec3 position, normal, to_eye;
  float exponent;
  bool dark;  // no light at all may reach the eye: diffuse and specular exactly 0
};

// n . h for an eye tilted by `angle` from the normal with the light along it: h lies at
// angle / 2, so n . h = cos(angle / 2).
inline glm::vec3 eye_tilted(float angle) { return {std::sin(angle), 0.f, std::cos(angle)}; }

inline std::vector<LightingCase> lighting_hard_cases() {
  const glm::vec3 up(0, 0, 1), origin(0);
  auto sun = [](glm::vec3 to_light) {
    return Light{.name = "sun", .type = LightType::Directional, .intensity = 2.f, .direction = -glm::normalize(to_light)};
  };
  auto lamp = [](glm::vec3 at) { return Light{.name = "lamp", .type = LightType::Point, .intensity = 3.f, .position = at}; };
  return {
      // The light 3 degrees below the horizon, the eye 45 degrees up on the other side: the
      // half vector is well above the surface (n . h = 0.91), so a specular that forgets
      // n . l <= 0 (or clamps it for the diffuse only) lights the surface from behind.
      {"light below the horizon, half vector above it", sun({0.9986f, 0, -0.0523f}), origin, up,
       glm::normalize(glm::vec3(-0.5f, 0, 0.5f)), 100.f, true},
      {"light behind the surface, eye along the normal", sun({0.3f, 0, -1}), origin, up, up, 10.f, true},
      // A lamp 1 mm inside the surface (a lamp mounted flush in a wall).
      {"lamp 1 mm inside the surface", lamp({0.3f, 0, -0.001f}), origin, up, up, 30.f, true},
      // A lamp exactly in the tangent plane: n . l = 0 exactly, so nothing, not a sliver.
      {"lamp in the tangent plane", lamp({2, 0, 0}), origin, up, glm::normalize(glm::vec3(-1, 0, 1)), 30.f, true},
      // A lamp at the shaded point itself: distance 0, the direction chosen as +y by convention
      // (here the normal), the inverse square held at 1 cm: finite, 10^4 x the intensity.
      {"lamp at the shaded point", lamp(origin), origin, {0, 1, 0}, {0, 1, 0}, 30.f, false},
      // The sharpest exponent the model makes (exponent_from_roughness's 8192 = 2^13) and far
      // beyond it: at h = n the lobe is its normalisation (n + 8) / 8 exactly; just off it,
      // pow's value, finite.
      {"exponent 2^13, h = n", sun(up), origin, up, up, 8192.f, false},
      {"exponent 2^13, h 0.5 degrees off n", sun(up), origin, up, eye_tilted(0.01745f), 8192.f, false},
      {"exponent 10^6, h = n", sun(up), origin, up, up, 1e6f, false},
      {"exponent 10^6, h 0.1 degrees off n", sun(up), origin, up, eye_tilted(0.00349f), 1e6f, false},
      {"exponent 10^30, h 2 degrees off n (pow underflows)", sun(up), origin, up, eye_tilted(0.0698f), 1e30f, false},
      // A degenerate normal (a mesh's zero normal, or two opposite normals interpolated):
      // n . l = 0, no light, and no NaN.
      {"zero normal", sun({0.3f, 0.2f, 1}), origin, glm::vec3(0), up, 30.f, true},
      // The eye exactly opposite the light (below the surface, as a silhouette's interpolated
      // normal can put it): l + v = 0 has no direction, so normalize(l + v) is 0 / 0.
      {"eye exactly opposite the light", sun({0.3f, 0, 1}), origin, up, -glm::normalize(glm::vec3(0.3f, 0, 1)), 30.f,
       false},
      // A lamp with a range, 2 m away of its 3: the window (1 - (d / r)^4)^2 = 0.645 and the
      // inverse square both apply (every other lamp here is unbounded: a window with another
      // power, or unsquared, would go unseen).
      {"lamp with a range, two thirds of the way to it",
       Light{.name = "lamp", .type = LightType::Point, .intensity = 3.f, .position = {0, 0, 2}, .range = 3.f}, origin, up,
       up, 30.f, false},
      // A spot whose falloff band holds the point: 0.29 rad off its axis, between the inner
      // cone's 0.1 and the outer's 0.5, so the cone's factor t^2 has t in (0, 1), not 0 or 1.
      {"spot, the point in its cone's falloff band",
       Light{.name = "spot", .type = LightType::Spot, .intensity = 3.f, .position = {0.6f, 0, 2}, .direction = {0, 0, -1},
             .inner_cone = 0.1f, .outer_cone = 0.5f},
       {1.2f, 0, 0}, up, up, 30.f, false},
      // The sun 60 degrees off the normal, the eye at its mirror image: h = n, so the lobe is
      // its peak and only n . l = 0.5 scales the specular (the cases above with light along
      // the normal have n . l = 1, where a specular without it is the same).
      {"sun 60 degrees off the normal, eye at its mirror", sun({0.866f, 0, 0.5f}), origin, up,
       glm::normalize(glm::vec3(-0.866f, 0, 0.5f)), 30.f, false},
  };
}

}  // namespace lp::test
