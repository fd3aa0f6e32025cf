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
  return from_root(given);
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
