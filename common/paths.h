#pragma once
// Where the book's files live. Programs never depend on the working directory: the source
// root is baked in at configure time, and LIGHTPASS_ROOT overrides it (e.g. for a copy of
// the tree on another machine).
#include <filesystem>
#include <string_view>

namespace lp {

std::filesystem::path source_root();

// A path relative to the source root ("assets/forward/forward.gltf"); absolute paths pass
// through unchanged.
std::filesystem::path from_root(const std::filesystem::path& relative);

// A file the reader names on the command line (--scene): relative to the current directory
// when it exists there, else to the source root (so "assets/forward/forward.gltf" works from
// any folder). Throws Error naming both paths when neither has the file.
std::filesystem::path resolve_input(const std::filesystem::path& given);

// Where shaders are found: #include "01_forward/shaders/x.glsl" is relative to this.
std::filesystem::path shader_root();

// Reads a whole text file; a missing file is reported with the full path that was tried.
std::string read_text_file(const std::filesystem::path& path, std::string_view what = "file");

}  // namespace lp
