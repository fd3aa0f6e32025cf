#include "common/paths.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "common/error.h"

namespace lp {

std::filesystem::path source_root() {
  if (const char* env = std::getenv("LIGHTPASS_ROOT"); env && *env) return env;
  return LIGHTPASS_SOURCE_ROOT;
}

std::filesystem::path from_root(const std::filesystem::path& relative) {
  if (relative.is_absolute()) return relative;
  return source_root() / relative;
}

std::filesystem::path resolve_input(const std::filesystem::path& given) {
  if (given.is_absolute()) return given;
  std::error_code ec;
  if (std::filesystem::exists(given, ec)) return given;
  const auto under_root = from_root(given);
  if (std::filesystem::exists(under_root, ec)) return under_root;
  // Neither place has it: name both, so the reader sees where it was looked for.
  throw Error("cannot open scene '" + given.string() + "': no such file in the current directory (" +
              (std::filesystem::current_path(ec) / given).lexically_normal().string() + ") nor under the source root (" +
              under_root.lexically_normal().string() + ")");
}

std::filesystem::path shader_root() { return source_root() / "chapters"; }

std::string read_text_file(const std::filesystem::path& path, std::string_view what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw Error("cannot open " + std::string(what) + " '" + path.string() +
                "': " + (std::filesystem::exists(path) ? "permission denied" : "no such file"));
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace lp
