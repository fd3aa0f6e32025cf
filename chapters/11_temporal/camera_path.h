#pragma once
// A deterministic camera path per scene: a few seconds at a fixed frame rate, keyed in the
// frame of one of the scene's named views, so frame N is the same image on every run and
// every machine. `--path walk` plays one (chapter 11's program, its tests and its sweep).
//
//   const CameraPath& path = path_named(scene, "walk");
//   for (int i = 0; i < path.frames(); ++i) { Camera c = path.camera(scene, i); bool cut = path.cut_at(i); ... }
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "common/scene.h"

namespace lp::ch11 {

// One key: at `t` seconds the camera stands at `offset` (metres, in the frame of the view
// `view`: x right, y up, -z ahead) turned by `yaw` (left, radians) and `pitch` (up).
// Between keys the pose moves smoothly; a key whose `view` differs from the previous key's
// is a camera cut: the image jumps, and temporal history must start again.
struct PathKey {
  float t = 0;
  std::string view;
  glm::vec3 offset{0};
  float yaw = 0, pitch = 0;
};

struct CameraPath {
  std::string name;
  std::string scene;  // the scene's file stem it is made for ("street_shop", "atrium")
  float fps = 30.f;
  std::vector<PathKey> keys;  // t ascending; the path lasts until the last key

  int frames() const;  // the frames of the path at fps, the last key's frame included
  // The pose at frame `i` (0 .. frames() - 1), from `scene`'s views. Throws lp::Error when a
  // key's view is not in the scene.
  Camera camera(const Scene& scene, int i) const;
  // True when frame `i` starts a new shot: the first frame, and the first frame after a cut.
  bool cut_at(int i) const;
};

// Every path made for the scene at `scene_path` (matched by its file stem), in a fixed order.
std::vector<CameraPath> paths_for(const std::string& scene_path);
// The names a program offers for --path ("off" first, then the union over the scenes).
std::vector<std::string> path_names();
// The path `name` of the scene; throws lp::Error saying which paths it has.
const CameraPath& path_named(const std::string& scene_path, const std::string& name);

}  // namespace lp::ch11
