#pragma once
// Move-only owners of OpenGL objects (DSA style, OpenGL 4.5). Each wrapper creates its
// object in the constructor and deletes it in the destructor; `id()` is the GL name.
#include <epoxy/gl.h>

#include <cstddef>
#include <string>
#include <utility>

namespace lp::gl {

template <class Traits>
class Object {
 public:
  Object() { id_ = Traits::create(); }
  explicit Object(GLenum target) { id_ = Traits::create(target); }
  ~Object() { reset(); }
  Object(Object&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  Object& operator=(Object&& o) noexcept {
    if (this != &o) { reset(); id_ = std::exchange(o.id_, 0); }
    return *this;
  }
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;
  GLuint id() const { return id_; }
  void reset() { if (id_) Traits::destroy(id_); id_ = 0; }

 private:
  GLuint id_ = 0;
};

#define LP_GL_TRAITS(Name, create_call, destroy_call)                   \
  struct Name##Traits {                                                 \
    static GLuint create() { GLuint id = 0; create_call(1, &id); return id; } \
    static void destroy(GLuint id) { destroy_call(1, &id); }            \
  };                                                                    \
  using Name = Object<Name##Traits>;

LP_GL_TRAITS(Buffer, glCreateBuffers, glDeleteBuffers)
LP_GL_TRAITS(VertexArray, glCreateVertexArrays, glDeleteVertexArrays)
LP_GL_TRAITS(Framebuffer, glCreateFramebuffers, glDeleteFramebuffers)
LP_GL_TRAITS(Renderbuffer, glCreateRenderbuffers, glDeleteRenderbuffers)
LP_GL_TRAITS(Sampler, glCreateSamplers, glDeleteSamplers)
#undef LP_GL_TRAITS

struct TextureTraits {
  static GLuint create(GLenum target) { GLuint id = 0; glCreateTextures(target, 1, &id); return id; }
  static void destroy(GLuint id) { glDeleteTextures(1, &id); }
};
using Texture = Object<TextureTraits>;

struct QueryTraits {
  static GLuint create(GLenum target) { GLuint id = 0; glCreateQueries(target, 1, &id); return id; }
  static void destroy(GLuint id) { glDeleteQueries(1, &id); }
};
using Query = Object<QueryTraits>;

struct ProgramTraits {
  static GLuint create() { return glCreateProgram(); }
  static void destroy(GLuint id) { glDeleteProgram(id); }
};
using Program = Object<ProgramTraits>;

// An immutable buffer filled once (vertex data, indices) or updated with glNamedBufferSubData.
inline Buffer make_buffer(const void* data, std::size_t bytes, GLbitfield flags = 0) {
  Buffer b;
  glNamedBufferStorage(b.id(), static_cast<GLsizeiptr>(bytes ? bytes : 1), data, flags);
  return b;
}

// A 2D texture with immutable storage; `levels` = 1 for render targets.
inline Texture make_texture_2d(GLenum internal_format, int w, int h, int levels = 1) {
  Texture t(GL_TEXTURE_2D);
  glTextureStorage2D(t.id(), levels, internal_format, w, h);
  return t;
}

// A render target of `samples` per pixel: above 1 a GL_TEXTURE_2D_MULTISAMPLE (fixed sample
// locations; no sampler state, read with texelFetch), else a one-level 2D texture.
inline Texture make_render_texture(GLenum internal_format, int w, int h, int samples) {
  if (samples <= 1) return make_texture_2d(internal_format, w, h);
  Texture t(GL_TEXTURE_2D_MULTISAMPLE);
  glTextureStorage2DMultisample(t.id(), samples, internal_format, w, h, GL_TRUE);
  return t;
}

// Bytes per texel of the render-target formats the book uses (for the "what did we allocate"
// report). Unknown formats return 0 so that a missing entry shows up as a zero, not a guess.
std::size_t bytes_per_texel(GLenum internal_format);

const char* error_name(GLenum error);

}  // namespace lp::gl
