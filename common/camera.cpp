#include "common/camera.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace lp {

FrameCamera frame_camera(const Camera& c, float aspect) {
  FrameCamera f;
  f.view = c.view();
  f.projection = glm::perspective(c.yfov, aspect, c.znear, c.zfar);
  f.position = c.position();
  f.yfov = c.yfov;
  f.znear = c.znear;
  f.zfar = c.zfar;
  f.aspect = aspect;
  return f;
}

FlyCamera::FlyCamera(const Camera& start, float speed) : base_(start), position_(start.position()), speed_(speed) {
  glm::vec3 forward = -glm::vec3(start.world[2]);
  yaw_ = std::atan2(forward.x, -forward.z);
  pitch_ = std::asin(std::clamp(forward.y, -1.f, 1.f));
}

void FlyCamera::update(GLFWwindow* w, float dt) {
  glm::vec3 forward(std::sin(yaw_) * std::cos(pitch_), std::sin(pitch_), -std::cos(yaw_) * std::cos(pitch_));
  glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
  float step = speed_ * dt * (glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ? 4.f : 1.f);
  auto held = [w](int key) { return glfwGetKey(w, key) == GLFW_PRESS ? 1.f : 0.f; };
  position_ += step * (forward * (held(GLFW_KEY_W) - held(GLFW_KEY_S)) + right * (held(GLFW_KEY_D) - held(GLFW_KEY_A)) +
                       glm::vec3(0, 1, 0) * (held(GLFW_KEY_E) - held(GLFW_KEY_Q)));
  double x, y;
  glfwGetCursorPos(w, &x, &y);
  bool down = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
  if (down && dragging_) {
    yaw_ += static_cast<float>(x - last_x_) * 0.004f;
    pitch_ = std::clamp(pitch_ - static_cast<float>(y - last_y_) * 0.004f, -1.55f, 1.55f);
  }
  dragging_ = down;
  last_x_ = x;
  last_y_ = y;
}

Camera FlyCamera::camera() const {
  Camera c = base_;
  glm::vec3 forward(std::sin(yaw_) * std::cos(pitch_), std::sin(pitch_), -std::cos(yaw_) * std::cos(pitch_));
  c.world = glm::inverse(glm::lookAt(position_, position_ + forward, glm::vec3(0, 1, 0)));
  return c;
}

}  // namespace lp
