#include "chapters/11_temporal/camera_path.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <glm/gtc/matrix_transform.hpp>

#include "common/error.h"

namespace lp::ch11 {

namespace {

// [paths]
// The paths, a few seconds each at 30 frames a second. "walk" moves ahead and aside past
// things that hide others (disocclusion), "pan" turns fast on the spot, "cut" holds one view
// and jumps to another halfway.
const std::vector<CameraPath>& all_paths() {
  static const std::vector<CameraPath> paths = {
      {"walk", "street_shop", 30.f, {{0.f, "shops", {0, 0, 0}, 0.f, 0.f}, {3.f, "shops", {2.5f, 0, -6}, 0.25f, 0.f}}},
      {"pan", "street_shop", 30.f, {{0.f, "street_level", {0, 0, 0}, 0.5f, 0.f}, {2.f, "street_level", {0, 0, 0}, -0.7f, 0.05f}}},
      {"cut", "street_shop", 30.f,
       {{0.f, "shops", {0, 0, 0}, 0.f, 0.f}, {1.f, "shops", {0.5f, 0, -2}, 0.05f, 0.f},
        {1.f, "shop_window", {0, 0, 0}, 0.f, 0.f}, {2.f, "shop_window", {0.3f, 0, -0.8f}, -0.05f, 0.f}}},
      {"walk", "atrium", 30.f, {{0.f, "aisle", {0, 0, 0}, 0.f, 0.f}, {3.f, "aisle", {1.5f, 0, -4}, 0.2f, 0.f}}},
      {"pan", "atrium", 30.f, {{0.f, "corner", {0, 0, 0}, 0.4f, 0.f}, {2.f, "corner", {0, 0, 0}, -0.8f, 0.f}}},
      {"cut", "atrium", 30.f,
       {{0.f, "aisle", {0, 0, 0}, 0.f, 0.f}, {1.f, "aisle", {0.5f, 0, -1.5f}, 0.05f, 0.f},
        {1.f, "corner", {0, 0, 0}, 0.f, 0.f}, {2.f, "corner", {-0.3f, 0, -0.8f}, -0.1f, 0.f}}},
  };
  return paths;
}
// [/paths]

std::string stem(const std::string& path) { return std::filesystem::path(path).stem().string(); }

float time_of(const CameraPath& p, int i) { return float(i) / p.fps; }

}  // namespace

int CameraPath::frames() const {
  if (keys.empty()) return 0;
  return int(std::lround(double(keys.back().t) * fps)) + 1;
}

// [pose]
Camera CameraPath::camera(const Scene& scene, int i) const {
  if (keys.empty()) throw Error("camera path " + name + " has no keys");
  const float t = time_of(*this, std::clamp(i, 0, frames() - 1));
  // The segment [a, b] holding t; across a cut (another view) the pose holds at a until b.
  std::size_t k = 0;
  while (k + 1 < keys.size() && keys[k + 1].t <= t) ++k;
  const PathKey& a = keys[k];
  const PathKey& b = k + 1 < keys.size() ? keys[k + 1] : a;
  const float s = (b.view != a.view || b.t <= a.t) ? 0.f : (t - a.t) / (b.t - a.t);
  const glm::vec3 offset = glm::mix(a.offset, b.offset, s);
  const float yaw = glm::mix(a.yaw, b.yaw, s), pitch = glm::mix(a.pitch, b.pitch, s);
  bool found = false;
  for (const Camera& c : scene.cameras) found = found || c.name == a.view;
  if (!found) throw Error("camera path " + name + ": the scene has no view named " + a.view);
  Camera c = scene.camera(a.view);
  const glm::mat4 base = c.world;
  glm::mat4 turn = glm::rotate(glm::mat4(1), yaw, glm::vec3(0, 1, 0));
  turn = glm::rotate(turn, pitch, glm::vec3(1, 0, 0));
  const glm::vec3 position = glm::vec3(base * glm::vec4(offset, 1.f));
  c.world = glm::translate(glm::mat4(1), position) * glm::mat4(glm::mat3(base)) * turn;
  return c;
}
// [/pose]

bool CameraPath::cut_at(int i) const {
  if (i <= 0) return true;
  const float t0 = time_of(*this, i - 1), t1 = time_of(*this, i);
  for (std::size_t k = 1; k < keys.size(); ++k)
    if (keys[k].view != keys[k - 1].view && keys[k].t > t0 && keys[k].t <= t1) return true;
  return false;
}

std::vector<CameraPath> paths_for(const std::string& scene_path) {
  std::vector<CameraPath> out;
  for (const CameraPath& p : all_paths())
    if (p.scene == stem(scene_path)) out.push_back(p);
  return out;
}

std::vector<std::string> path_names() {
  std::vector<std::string> names = {"off"};
  for (const CameraPath& p : all_paths())
    if (std::find(names.begin(), names.end(), p.name) == names.end()) names.push_back(p.name);
  return names;
}

const CameraPath& path_named(const std::string& scene_path, const std::string& name) {
  std::string have;
  for (const CameraPath& p : all_paths()) {
    if (p.scene != stem(scene_path)) continue;
    if (p.name == name) return p;
    have += (have.empty() ? "" : ", ") + p.name;
  }
  throw Error("no camera path named " + name + " for the scene " + scene_path +
              (have.empty() ? std::string(" (it has none)") : " (it has: " + have + ")"));
}

}  // namespace lp::ch11
