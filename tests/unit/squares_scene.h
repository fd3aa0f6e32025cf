#pragma once
// Test scenes of chapters 07 and 08 made of flat squares (one-sided quads), built in code.
//
// roof_hole_scene: every occluder (and emitter) a receiver sees lies at one view depth well in
// front of it: a floor under a flat roof with a square hole, seen from straight above through
// the hole. The receivers are the floor's pixels inside the hole; the samples their
// screen-space disks put on the roof are at view depth ze = eye - roof, the floor's at zr =
// eye, so ze / zr is far from 1 (0.6 by default), where the Cornell box's views have it near 1.
// The roof's squares face up: the raster sees their top, the ray tracer's rays from the floor
// hit the same plane from below, so the truth and the method see the roof at the same height.
// The floor is coplanar with every other floor pixel (cosine 0), so the roof is all that
// occludes.
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "common/camera.h"
#include "common/scene.h"

namespace lp::test {

struct RoofHole {
  float eye = 1.f;         // the camera's height above the floor, looking straight down
  float roof = 0.4f;       // the roof's height
  float half_hole = 0.12f; // the hole is |x|, |z| < half_hole
  float size = 3.f;        // floor and roof reach |x|, |z| < size
  float yfov = 1.2f;       // wide: R = 0.5 projects to a third of the image height
};

// A scene of one grey material (albedo 0.5) and one unit square in the XZ plane facing +y, placed
// by each instance's matrix (add_square); no lights.
inline Scene squares_scene(const std::string& path) {
  Scene s;
  s.path = path;
  s.materials = {Material{.name = "grey", .base_color = glm::vec4(0.5f, 0.5f, 0.5f, 1)}};
  for (glm::vec2 c : {glm::vec2(0, 0), glm::vec2(0, 1), glm::vec2(1, 1), glm::vec2(1, 0)})
    s.vertices.push_back(Vertex{glm::vec3(c.x, 0, c.y), glm::vec3(0, 1, 0), c, glm::vec4(1, 0, 0, 1)});
  s.indices = {0, 1, 2, 0, 2, 3};
  s.meshes.push_back(Mesh{"square", {Primitive{0, 6, 0}}});
  return s;
}
inline void add_square(Scene& s, const std::string& name, const glm::mat4& model, glm::vec3 lo, glm::vec3 hi) {
  s.instances.push_back(Instance{name, 0, model, {}});
  s.bounds_min = s.instances.size() == 1 ? lo : glm::min(s.bounds_min, lo);
  s.bounds_max = s.instances.size() == 1 ? hi : glm::max(s.bounds_max, hi);
}
inline Light directional(const std::string& name, glm::vec3 direction, float lux) {
  Light l;
  l.name = name;
  l.type = LightType::Directional;
  l.intensity = lux;
  l.direction = glm::normalize(direction);
  return l;
}

inline Scene roof_hole_scene(const RoofHole& r = {}) {
  Scene s = squares_scene("roof with a hole (test)");
  const auto rect = [&](const std::string& name, float x0, float x1, float z0, float z1, float y) {
    const glm::mat4 m = glm::scale(glm::translate(glm::mat4(1), glm::vec3(x0, y, z0)), glm::vec3(x1 - x0, 1, z1 - z0));
    add_square(s, name, m, glm::vec3(x0, y, z0), glm::vec3(x1, y, z1));
  };
  const float a = r.half_hole, w = r.size;
  rect("floor", -w, w, -w, w, 0.f);
  rect("roof", -w, -a, -w, w, r.roof);
  rect("roof", a, w, -w, w, r.roof);
  rect("roof", -a, a, -w, -a, r.roof);
  rect("roof", -a, a, a, w, r.roof);
  s.lights.push_back(directional("sun", glm::vec3(0.3f, -1.f, 0.2f), 2.f));
  s.ambient = glm::vec3(0.1f);
  return s;
}

inline FrameCamera roof_hole_camera(const RoofHole& r, float aspect) {
  Camera c;
  c.world = glm::inverse(glm::lookAt(glm::vec3(0, r.eye, 0), glm::vec3(0), glm::vec3(0, 0, -1)));
  c.yfov = r.yfov, c.znear = 0.05f, c.zfar = 10.f;
  return frame_camera(c, aspect);
}

}  // namespace lp::test
