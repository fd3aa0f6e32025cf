#include "common/gl.h"

namespace lp::gl {

std::size_t bytes_per_texel(GLenum f) {
  switch (f) {
    case GL_R8: return 1;
    case GL_RG8: case GL_R16F: case GL_R16: case GL_DEPTH_COMPONENT16: return 2;
    case GL_RGBA8: case GL_SRGB8_ALPHA8: case GL_RGB10_A2: case GL_RG16F: case GL_RG16:
    case GL_RG16_SNORM: case GL_R32F: case GL_R11F_G11F_B10F: case GL_DEPTH24_STENCIL8:
    case GL_DEPTH_COMPONENT24: case GL_DEPTH_COMPONENT32F: case GL_R32UI: return 4;
    case GL_DEPTH32F_STENCIL8: return 5;  // 32-bit depth + 8-bit stencil (drivers pad it to 8)
    case GL_RGBA16F: case GL_RG32F: case GL_RGBA16: return 8;
    case GL_RGBA32F: return 16;
    default: return 0;
  }
}

const char* error_name(GLenum e) {
  switch (e) {
    case GL_NO_ERROR: return "GL_NO_ERROR";
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    default: return "unknown GL error";
  }
}

}  // namespace lp::gl
