#pragma once
// GLSL 450 programs loaded from the source tree at run time, so a reader can edit a shader
// and run again (or press R in the window). `#include "01_forward/shaders/x.glsl"` is
// resolved from chapters/. Compile and link errors name the original file and line.
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "common/gl.h"

namespace lp {

struct ShaderStage {
  GLenum type;          // GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, ...
  std::string path;     // relative to chapters/, e.g. "01_forward/shaders/forward.vert"
};

// A preprocessed source: the text handed to the driver and, for each source-string number
// used in its #line directives, the file it came from.
struct ShaderSource {
  std::string text;
  std::vector<std::string> files;
};

// Expands #include (recursively, each file once) and inserts `defines` after #version.
// `#include NAME` includes the file that the define `NAME "path"` names (an error when none does,
// except inside `#ifdef NAME`: there an absent NAME leaves the line out, as GLSL would).
ShaderSource preprocess_shader(const std::string& path, const std::vector<std::string>& defines = {});

// Defines added to every program the process builds from now on, after its own: how
// `--exercise K` puts a reader's file in place of a chapter's function (common/app.h).
void set_program_wide_defines(std::vector<std::string> defines);

// Rewrites a driver's info log so that "0:12(3): error" (Mesa) or "0(12) : error" (NVIDIA)
// reads "01_forward/shaders/forward.frag:12: error".
std::string map_shader_log(const std::string& log, const std::vector<std::string>& files);

// What ShaderProgram::reload() did since the last call: how many programs were rebuilt, how
// many failed, and the first failure's message (file and line). R in the window says it.
struct ReloadTally {
  int reloaded = 0, failed = 0;
  std::string first_error;
};
ReloadTally take_reload_tally();

class ShaderProgram {
 public:
  ShaderProgram() = default;
  // Throws Error naming the file and line of the first problem.
  ShaderProgram(std::vector<ShaderStage> stages, std::vector<std::string> defines = {});

  // Recompiles from disk; on failure prints the error, keeps the old program, returns false.
  bool reload();
  GLuint id() const { return program_.id(); }
  void use() const { glUseProgram(program_.id()); }

  GLint location(const char* name) const { return glGetUniformLocation(program_.id(), name); }
  void set(const char* name, int v) const { glProgramUniform1i(id(), location(name), v); }
  void set(const char* name, float v) const { glProgramUniform1f(id(), location(name), v); }
  void set(const char* name, const glm::vec2& v) const { glProgramUniform2fv(id(), location(name), 1, &v.x); }
  void set(const char* name, const glm::vec3& v) const { glProgramUniform3fv(id(), location(name), 1, &v.x); }
  void set(const char* name, const glm::vec4& v) const { glProgramUniform4fv(id(), location(name), 1, &v.x); }
  void set(const char* name, const glm::mat3& m) const { glProgramUniformMatrix3fv(id(), location(name), 1, GL_FALSE, &m[0][0]); }
  void set(const char* name, const glm::mat4& m) const { glProgramUniformMatrix4fv(id(), location(name), 1, GL_FALSE, &m[0][0]); }

 private:
  static gl::Program build(const std::vector<ShaderStage>& stages, const std::vector<std::string>& defines);
  std::vector<ShaderStage> stages_;
  std::vector<std::string> defines_;
  gl::Program program_;
};

// Programs made when first asked for, one per set of stages and defines (a stage or chapter
// that compiles variants: per layout, per hook, per output). References stay valid until
// clear().
class ProgramCache {
 public:
  const ShaderProgram& get(const std::vector<ShaderStage>& stages, const std::vector<std::string>& defines = {});
  void reload();                     // every program from disk again (R in the window); a failure keeps the old one
  void clear() { programs_.clear(); }  // forget them all: each is made again, from disk, when next asked for

 private:
  std::map<std::string, ShaderProgram> programs_;
};

}  // namespace lp
