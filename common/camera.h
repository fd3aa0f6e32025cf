#pragma once
// The camera a frame is rendered with, and a fly camera for the window
// (W/A/S/D/Q/E to move, right mouse button to look, Shift to go faster).
#include <glm/glm.hpp>

#include "common/scene.h"

struct GLFWwindow;

namespace lp {

struct FrameCamera {
  glm::mat4 view{1}, projection{1};
  glm::vec3 position{0};
  float yfov = 0.8f, znear = 0.1f, zfar = 1000.f, aspect = 16.f / 9.f;
  glm::mat4 view_projection() const { return projection * view; }
};

// A glTF camera at the given aspect ratio (OpenGL clip space, depth -1..1).
FrameCamera frame_camera(const Camera& camera, float aspect);

class FlyCamera {
 public:
  FlyCamera() = default;
  FlyCamera(const Camera& start, float speed);  // speed in metres per second
  void update(GLFWwindow* window, float seconds);
  Camera camera() const;  // the current pose, as a glTF camera

 private:
  Camera base_;
  glm::vec3 position_{0};
  float yaw_ = 0, pitch_ = 0, speed_ = 1;
  double last_x_ = 0, last_y_ = 0;
  bool dragging_ = false;
};

}  // namespace lp
