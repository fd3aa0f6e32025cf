#include "common/shader.h"

#include <algorithm>
#include <iostream>
#include <regex>
#include <sstream>
#include <utility>

#include "common/error.h"
#include "common/paths.h"

namespace lp {
namespace {

std::vector<std::string> g_program_wide_defines;

struct Preprocessor {
  std::vector<std::string> files;
  std::vector<std::string> stack;  // to report include cycles
  std::vector<std::string> defines;

  // `#include NAME`: the file a define names, `NAME "path"` (as C's computed includes).
  // This is how a later chapter plugs its GLSL into an earlier chapter's shader.
  std::string included_by_define(const std::string& name, const std::string& where) const {
    for (const auto& d : defines) {
      if (d.compare(0, name.size(), name) != 0 || d.size() <= name.size() || d[name.size()] != ' ') continue;
      static const std::regex quoted(R"re(^\s*"([^"]+)"\s*$)re");
      std::smatch m;
      std::string value = d.substr(name.size() + 1);
      if (!std::regex_match(value, m, quoted))
        throw Error(where + ": #include " + name + ": the define " + name + " must be a quoted path, not " + value);
      return m[1];
    }
    throw Error(where + ": #include " + name + ": " + name + " is not defined (the program must pass it as a define)");
  }

  bool is_defined(const std::string& name) const {
    return std::any_of(defines.begin(), defines.end(), [&](const std::string& d) {
      return d.compare(0, name.size(), name) == 0 && (d.size() == name.size() || d[name.size()] == ' ');
    });
  }

  int file_index(const std::string& path) {
    auto it = std::find(files.begin(), files.end(), path);
    if (it != files.end()) return static_cast<int>(it - files.begin());
    files.push_back(path);
    return static_cast<int>(files.size() - 1);
  }

  // Appends `path` to `out`, expanding includes; `included_from` names the including line.
  void expand(const std::string& path, const std::string& included_from, std::ostringstream& out, bool root) {
    if (std::find(stack.begin(), stack.end(), path) != stack.end())
      throw Error(included_from + ": #include \"" + path + "\" includes itself (cycle)");
    bool already = std::find(files.begin(), files.end(), path) != files.end();
    if (already) return;  // each file once, like #pragma once
    std::string text;
    try {
      text = read_text_file(shader_root() / path, "shader");
    } catch (const Error& e) {
      throw Error(included_from.empty() ? e.what() : included_from + ": " + e.what());
    }
    int id = file_index(path);
    if (!stack.empty()) out << "#line 1 " << id << '\n';  // the root file starts with #version
    stack.push_back(path);
    std::istringstream in(text);
    std::string line;
    int number = 0;
    static const std::regex include_re(R"(^\s*#\s*include\s+"([^"]+)\"\s*$)");
    static const std::regex computed_include_re(R"(^\s*#\s*include\s+([A-Za-z_][A-Za-z0-9_]*)\s*(//.*)?$)");
    static const std::regex version_re(R"(^\s*#\s*version\b.*)");
    static const std::regex if_re(R"(^\s*#\s*(ifdef|ifndef|if)\b\s*([A-Za-z_][A-Za-z0-9_]*)?.*)");
    static const std::regex else_re(R"(^\s*#\s*(else|elif)\b.*)");
    static const std::regex endif_re(R"(^\s*#\s*endif\b.*)");
    // The open conditionals: the name of an `#ifdef NAME` whose first branch we are in, else "".
    std::vector<std::string> ifdefs;
    bool version_seen = false;
    while (std::getline(in, line)) {
      ++number;
      std::smatch m;
      if (std::regex_match(line, m, include_re)) {
        expand(m[1], path + ":" + std::to_string(number), out, false);
        out << "#line " << number + 1 << ' ' << id << '\n';
      } else if (std::regex_match(line, m, computed_include_re)) {
        const std::string where = path + ":" + std::to_string(number);
        if (!is_defined(m[1]) && std::find(ifdefs.begin(), ifdefs.end(), m[1].str()) != ifdefs.end()) {
          out << "// #include " << m[1] << " (not defined)\n";  // GLSL skips this branch too
          continue;
        }
        expand(included_by_define(m[1], where), where, out, false);
        out << "#line " << number + 1 << ' ' << id << '\n';
      } else if (!version_seen && root && std::regex_match(line, version_re)) {
        version_seen = true;
        out << line << '\n';
        for (const auto& d : defines) out << "#define " << d << '\n';
        out << "#line " << number + 1 << ' ' << id << '\n';
      } else {
        if (std::regex_match(line, m, if_re)) ifdefs.push_back(m[1] == "ifdef" ? m[2].str() : "");
        else if (std::regex_match(line, else_re) && !ifdefs.empty()) ifdefs.back() = "";
        else if (std::regex_match(line, endif_re) && !ifdefs.empty()) ifdefs.pop_back();
        out << line << '\n';
      }
    }
    stack.pop_back();
  }
};

std::string stage_name(GLenum type) {
  switch (type) {
    case GL_VERTEX_SHADER: return "vertex";
    case GL_FRAGMENT_SHADER: return "fragment";
    case GL_GEOMETRY_SHADER: return "geometry";
    case GL_COMPUTE_SHADER: return "compute";
    default: return "shader";
  }
}

}  // namespace

ShaderSource preprocess_shader(const std::string& path, const std::vector<std::string>& defines) {
  Preprocessor p;
  p.defines = defines;
  p.defines.insert(p.defines.end(), g_program_wide_defines.begin(), g_program_wide_defines.end());
  std::ostringstream out;
  p.expand(path, "", out, true);
  return {out.str(), p.files};
}

void set_program_wide_defines(std::vector<std::string> defines) { g_program_wide_defines = std::move(defines); }

std::string map_shader_log(const std::string& log, const std::vector<std::string>& files) {
  // Mesa: "0:12(3): error: ..."   NVIDIA: "0(12) : error C1008: ..."
  static const std::regex mesa(R"(^(\d+):(\d+)\((\d+)\):\s*(.*)$)");
  static const std::regex nvidia(R"(^(\d+)\((\d+)\)\s*:\s*(.*)$)");
  std::istringstream in(log);
  std::ostringstream out;
  std::string line;
  auto file = [&](const std::string& index) {
    size_t i = std::stoul(index);
    return i < files.size() ? files[i] : "<source " + index + ">";
  };
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_match(line, m, mesa))
      out << file(m[1]) << ':' << m[2] << ':' << m[3] << ": " << m[4] << '\n';
    else if (std::regex_match(line, m, nvidia))
      out << file(m[1]) << ':' << m[2] << ": " << m[3] << '\n';
    else if (!line.empty())
      out << line << '\n';
  }
  return out.str();
}

ShaderProgram::ShaderProgram(std::vector<ShaderStage> stages, std::vector<std::string> defines)
    : stages_(std::move(stages)), defines_(std::move(defines)), program_(build(stages_, defines_)) {}

namespace {
ReloadTally g_reload_tally;  // the window's one GL thread reloads; nothing else touches it
}  // namespace

ReloadTally take_reload_tally() { return std::exchange(g_reload_tally, {}); }

bool ShaderProgram::reload() {
  try {
    program_ = build(stages_, defines_);
    ++g_reload_tally.reloaded;
    return true;
  } catch (const Error& e) {
    std::cerr << e.what() << "\n(kept the previous program)\n";
    if (g_reload_tally.failed++ == 0) g_reload_tally.first_error = e.what();
    return false;
  }
}

gl::Program ShaderProgram::build(const std::vector<ShaderStage>& stages, const std::vector<std::string>& defines) {
  gl::Program program;
  std::vector<GLuint> shaders;
  std::vector<std::string> all_files;
  auto cleanup = [&] { for (GLuint s : shaders) glDeleteShader(s); };
  for (const auto& stage : stages) {
    ShaderSource src;
    try {
      src = preprocess_shader(stage.path, defines);
    } catch (...) {
      cleanup();
      throw;
    }
    GLuint s = glCreateShader(stage.type);
    shaders.push_back(s);
    const char* text = src.text.c_str();
    glShaderSource(s, 1, &text, nullptr);
    glCompileShader(s);
    GLint ok = 0, length = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      glGetShaderiv(s, GL_INFO_LOG_LENGTH, &length);
      std::string log(std::max(length, 1), '\0');
      glGetShaderInfoLog(s, length, nullptr, log.data());
      cleanup();
      throw Error("cannot compile " + stage_name(stage.type) + " shader " +
                  (shader_root() / stage.path).string() + ":\n" + map_shader_log(log.c_str(), src.files));
    }
    glAttachShader(program.id(), s);
    all_files.insert(all_files.end(), src.files.begin(), src.files.end());
  }
  glLinkProgram(program.id());
  cleanup();
  GLint ok = 0, length = 0;
  glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  if (!ok) {
    glGetProgramiv(program.id(), GL_INFO_LOG_LENGTH, &length);
    std::string log(std::max(length, 1), '\0');
    glGetProgramInfoLog(program.id(), length, nullptr, log.data());
    std::string names;
    for (const auto& s : stages) names += " " + s.path;
    throw Error("cannot link shader program (" + names.substr(1) + "):\n" + log.c_str());
  }
  return program;
}

const ShaderProgram& ProgramCache::get(const std::vector<ShaderStage>& stages, const std::vector<std::string>& defines) {
  std::string key;
  for (const ShaderStage& st : stages) key += std::to_string(st.type) + ":" + st.path + "|";
  for (const std::string& d : defines) key += "|" + d;
  auto it = programs_.find(key);
  if (it == programs_.end()) it = programs_.emplace(key, ShaderProgram(stages, defines)).first;
  return it->second;
}

void ProgramCache::reload() {
  for (auto& [key, program] : programs_) program.reload();
}

}  // namespace lp
