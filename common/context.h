#pragma once
// An OpenGL 4.5 core context, either in a GLFW window or headless through EGL, behind one
// interface so that the window, the tests and the book's figures run the same code path.
#include <memory>
#include <string>

struct GLFWwindow;

namespace lp {

struct ContextRequest {
  bool headless = false;
  int width = 1280, height = 720;
  std::string title = "lightpass";
};

class Context {
 public:
  virtual ~Context() = default;
  // A window when a display is there and headless was not asked for; otherwise EGL (the
  // device platform first, which finds a real GPU, then Mesa's surfaceless platform).
  // Prints why it fell back to headless. Throws Error when no context can be made at all.
  static std::unique_ptr<Context> create(const ContextRequest& request);

  virtual bool is_window() const = 0;
  virtual GLFWwindow* window() const { return nullptr; }
  virtual bool should_close() const { return false; }
  virtual void swap_and_poll() {}
  // Framebuffer size in pixels; 0x0 while a window is minimised.
  virtual void framebuffer_size(int& w, int& h) const = 0;
  // Which EGL platform or window system made it, e.g. "EGL device (NVIDIA)".
  virtual std::string platform() const = 0;

  std::string renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string version() const;   // GL_VERSION
  bool is_software() const;      // llvmpipe / softpipe: timings are CPU timings
};

}  // namespace lp
