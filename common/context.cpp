#include "common/context.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <cstring>
#include <iostream>
#include <vector>

#include "common/error.h"

namespace lp {
namespace {

#ifndef NDEBUG
void GLAPIENTRY debug_callback(GLenum, GLenum type, GLuint, GLenum severity, GLsizei,
                               const GLchar* message, const void*) {
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
  std::cerr << (type == GL_DEBUG_TYPE_ERROR ? "GL error: " : "GL: ") << message << '\n';
}
#endif

void enable_debug_output() {
#ifndef NDEBUG
  if (epoxy_has_gl_extension("GL_KHR_debug") || epoxy_gl_version() >= 43) {
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(debug_callback, nullptr);
  }
#endif
}

void require_gl45() {
  if (epoxy_gl_version() < 45) {
    const char* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    throw Error(std::string("OpenGL 4.5 is required, but '") + (r ? r : "?") + "' offers " +
                std::to_string(epoxy_gl_version() / 10) + "." + std::to_string(epoxy_gl_version() % 10) +
                " (macOS stops at 4.1; elsewhere Mesa's llvmpipe provides 4.5 in software)");
  }
}

class EglContext final : public Context {
 public:
  explicit EglContext(const ContextRequest& r) : width_(r.width), height_(r.height) {
    if (!try_device_platform() && !try_platform(EGL_PLATFORM_SURFACELESS_MESA, nullptr, "EGL surfaceless (Mesa)"))
      throw Error("no headless OpenGL 4.5 context: neither EGL_EXT_platform_device nor "
                  "EGL_MESA_platform_surfaceless gave one. On Debian: apt-get install libegl-mesa0 libgl1-mesa-dri");
    enable_debug_output();
    require_gl45();
  }
  ~EglContext() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }
  bool is_window() const override { return false; }
  void framebuffer_size(int& w, int& h) const override { w = width_; h = height_; }
  std::string platform() const override { return platform_; }

 private:
  // Hardware devices first; Mesa's software device only if nothing else works.
  bool try_device_platform() {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!client || !std::strstr(client, "EGL_EXT_platform_device")) return false;
    EGLint count = 0;
    if (!eglQueryDevicesEXT(0, nullptr, &count) || count == 0) return false;
    std::vector<EGLDeviceEXT> devices(count);
    eglQueryDevicesEXT(count, devices.data(), &count);
    // LIGHTPASS_SOFTWARE=1 (set by ./test) keeps to Mesa's llvmpipe, the renderer the
    // reference images were made with, even on a machine with a GPU.
    const char* only_software = std::getenv("LIGHTPASS_SOFTWARE");
    bool software_only = only_software && std::string(only_software) == "1";
    for (bool software : {false, true}) {
      if (software_only && !software) continue;
      for (EGLDeviceEXT d : devices) {
        const char* ext = eglQueryDeviceStringEXT(d, EGL_EXTENSIONS);
        bool is_software = ext && std::strstr(ext, "EGL_MESA_device_software");
        if (is_software != software) continue;
        if (try_platform(EGL_PLATFORM_DEVICE_EXT, d, software ? "EGL device (software)" : "EGL device")) return true;
      }
    }
    return false;
  }

  bool try_platform(EGLenum platform, void* native, const char* name) {
    EGLDisplay dpy = eglGetPlatformDisplayEXT(platform, native, nullptr);
    if (dpy == EGL_NO_DISPLAY) return false;
    EGLint major = 0, minor = 0;
    if (!eglInitialize(dpy, &major, &minor)) return false;
    if (!eglBindAPI(EGL_OPENGL_API)) { eglTerminate(dpy); return false; }
    const EGLint attribs[] = {
        EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
#ifndef NDEBUG
        EGL_CONTEXT_OPENGL_DEBUG, EGL_TRUE,
#endif
        EGL_NONE};
    // Surfaceless: we render into our own framebuffer objects, so no config is needed.
    EGLContext ctx = eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    if (ctx == EGL_NO_CONTEXT || !eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
      if (ctx != EGL_NO_CONTEXT) eglDestroyContext(dpy, ctx);
      eglTerminate(dpy);
      return false;
    }
    display_ = dpy;
    context_ = ctx;
    platform_ = name;
    return true;
  }

  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  std::string platform_;
  int width_, height_;
};

class GlfwContext final : public Context {
 public:
  explicit GlfwContext(GLFWwindow* w) : window_(w) {
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(1);
    enable_debug_output();
    require_gl45();
  }
  ~GlfwContext() override {
    glfwDestroyWindow(window_);
    glfwTerminate();
  }
  bool is_window() const override { return true; }
  GLFWwindow* window() const override { return window_; }
  bool should_close() const override { return glfwWindowShouldClose(window_); }
  void swap_and_poll() override {
    glfwSwapBuffers(window_);
    glfwPollEvents();
  }
  void framebuffer_size(int& w, int& h) const override { glfwGetFramebufferSize(window_, &w, &h); }
  std::string platform() const override { return "GLFW window"; }

 private:
  GLFWwindow* window_;
};

// Returns a window, or nullptr with the reason printed.
GLFWwindow* open_window(const ContextRequest& r) {
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((!display || !*display) && (!wayland || !*wayland)) {
    std::cerr << "note: no display (DISPLAY and WAYLAND_DISPLAY are unset): rendering headless\n";
    return nullptr;
  }
  glfwSetErrorCallback([](int, const char* msg) { std::cerr << "GLFW: " << msg << '\n'; });
  if (!glfwInit()) {
    std::cerr << "note: cannot open the display: rendering headless\n";
    return nullptr;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
#ifndef NDEBUG
  glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
#endif
  GLFWwindow* w = glfwCreateWindow(r.width, r.height, r.title.c_str(), nullptr, nullptr);
  if (!w) {
    std::cerr << "note: the display offers no OpenGL 4.5 core window: rendering headless\n";
    glfwTerminate();
  }
  return w;
}

}  // namespace

std::unique_ptr<Context> Context::create(const ContextRequest& request) {
  if (!request.headless) {
    if (GLFWwindow* w = open_window(request)) return std::make_unique<GlfwContext>(w);
  }
  return std::make_unique<EglContext>(request);
}

std::string Context::renderer() const { return reinterpret_cast<const char*>(glGetString(GL_RENDERER)); }
std::string Context::version() const { return reinterpret_cast<const char*>(glGetString(GL_VERSION)); }
bool Context::is_software() const {
  auto r = renderer();
  return r.find("llvmpipe") != std::string::npos || r.find("softpipe") != std::string::npos;
}

}  // namespace lp
