#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE_WRITE
#include <tiny_gltf.h>

#include "common/scene.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <iomanip>
#include <sstream>
#include <string_view>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include "common/error.h"

namespace lp {
namespace {

namespace fs = std::filesystem;

// Sizes from the file are 64-bit and hostile: every sum and product that decides whether a
// read stays inside a buffer is checked, so offsets near 2^64 cannot wrap around the check.
bool add(std::size_t a, std::size_t b, std::size_t& out) { return !__builtin_add_overflow(a, b, &out); }
bool mul(std::size_t a, std::size_t b, std::size_t& out) { return !__builtin_mul_overflow(a, b, &out); }

bool finite(float v) { return std::isfinite(v); }
template <int N>
bool finite(const glm::vec<N, float>& v) {
  for (int i = 0; i < N; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}
bool finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    if (!finite(m[c])) return false;
  return true;
}

std::string number_text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// Reads a whole regular file, saying why it cannot: a directory, a device such as /dev/null,
// a file this user may not read, or one larger than the loader accepts. Empty: fine.
std::string read_problem(const fs::path& path, std::vector<unsigned char>* out, std::size_t max_bytes) {
  std::error_code ec;
  auto status = fs::status(path, ec);
  // A loop of symbolic links, or a folder that may not be searched, is not "no such file".
  if (ec && ec != std::errc::no_such_file_or_directory && ec != std::errc::not_a_directory) return ec.message();
  if (ec || !fs::exists(status)) return "no such file";
  if (fs::is_directory(status)) return "it is a directory";
  if (!fs::is_regular_file(status)) return "not a regular file";
  auto size = fs::file_size(path, ec);
  if (ec) return ec.message();
  if (size > max_bytes)
    return "the file is " + std::to_string(size) + " bytes, more than the loader accepts (" + std::to_string(max_bytes) + ")";
  std::ifstream in(path, std::ios::binary);
  if (!in) return errno == EACCES ? "permission denied" : std::strerror(errno);
  out->resize(size);
  if (size && !in.read(reinterpret_cast<char*>(out->data()), std::streamsize(size))) return "read error";
  return "";
}

// tinygltf's file access, through read_problem: its own reads a directory as a file of
// 2^63 bytes (std::bad_alloc) and says "File not found" for a file it may not read.
struct FileContext {
  std::size_t max_bytes = 0;
  std::string base;  // the scene's folder, which tinygltf puts before every URI
  std::vector<std::string> problems;  // "cannot read <path>: <why>", in the order met
};

bool fs_exists(const std::string& path, void* user) {
  std::error_code ec;
  if (fs::exists(path, ec)) return true;
  // Said by us, not as tinygltf's "File not found": which path, and why.
  std::vector<unsigned char> none;
  static_cast<FileContext*>(user)->problems.push_back("cannot read '" + path + "': " + read_problem(path, &none, 0));
  return false;
}
// No ~ or $VAR expansion. A URI that is an absolute path ("/dev/zero") names that path, as a
// relative reference resolves against the file's folder (RFC 3986); tinygltf joins it to the folder.
std::string fs_expand(const std::string& path, void* user) {
  const std::string& base = static_cast<FileContext*>(user)->base;
  if (!base.empty() && base.back() != '/' && path.size() > base.size() + 1 && path.compare(0, base.size(), base) == 0 &&
      path[base.size()] == '/' && path[base.size() + 1] == '/')
    return path.substr(base.size() + 1);
  return path;
}
bool fs_read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  std::string why = read_problem(path, out, static_cast<FileContext*>(user)->max_bytes);
  if (why.empty()) return true;
  std::string message = "cannot read '" + path + "': " + why;
  if (err) *err += message;
  static_cast<FileContext*>(user)->problems.push_back(message);
  return false;
}
bool fs_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "the loader writes no files";
  return false;
}

// Decodes images with stb_image, always to 8-bit RGBA (16-bit PNGs are converted), and
// refuses sizes past SceneLimits before decoding. A picture that cannot be used is not an
// error: the image stays empty, the reason is kept, and the material gets a fallback.
struct ImageContext {
  tinygltf::Model* model = nullptr;
  SceneLimits limits;
  std::map<int, std::string> problems;   // image index -> why it is empty
  std::vector<std::string> converted;    // 16-bit images read as 8 bits
  // Images whose bytes equal an earlier image's (one file named by many images): decoded and
  // counted once, the later ones left empty and pointing at the first.
  std::map<std::pair<std::size_t, std::size_t>, int> first_of_content;  // (size, hash) -> image
  std::map<int, int> same_as;
  std::size_t total_texels = 0;          // of the distinct images decoded so far
};

bool load_image(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                const unsigned char* bytes, int size, void* user) {
  auto& ctx = *static_cast<ImageContext*>(user);
  const SceneLimits& limits = ctx.limits;
  std::string name = !image->uri.empty() ? image->uri : !image->name.empty() ? image->name : "image " + std::to_string(index);
  if (image->bufferView >= 0) {
    // tinygltf hands over &buffer[byteOffset] with byteLength unchecked: check them here.
    const auto& m = *ctx.model;
    std::size_t end = 0;
    bool inside = std::size_t(image->bufferView) < m.bufferViews.size();
    if (inside) {
      const auto& view = m.bufferViews[std::size_t(image->bufferView)];
      inside = view.buffer >= 0 && std::size_t(view.buffer) < m.buffers.size() && add(view.byteOffset, view.byteLength, end) &&
               end <= m.buffers[std::size_t(view.buffer)].data.size();
    }
    if (!inside) {
      if (err) *err += "image " + std::to_string(index) + " ('" + name + "'): its bufferView " + std::to_string(image->bufferView) +
                       " does not lie inside its buffer\n";
      return false;
    }
  }
  image->image.clear();
  image->width = image->height = 0;
  // The same bytes again: share the first decode. (A 64-bit hash: a collision, which only a
  // file made for it could cause, shows one of its images in place of another.)
  if (size > 0) {
    const auto key = std::make_pair(std::size_t(size), std::hash<std::string_view>{}(
                                                           std::string_view(reinterpret_cast<const char*>(bytes), std::size_t(size))));
    auto [it, fresh] = ctx.first_of_content.emplace(key, index);
    if (!fresh) {
      ctx.same_as[index] = it->second;
      return true;
    }
  }
  int w = 0, h = 0, channels = 0;
  // stb_image refuses a PNG past 2^30 bytes as "unknown image type": its header says the size.
  if (size >= 24 && std::memcmp(bytes, "\x89PNG\r\n\x1A\n", 8) == 0 && std::memcmp(bytes + 12, "IHDR", 4) == 0) {
    auto be32 = [&](int at) { return std::uint32_t(bytes[at]) << 24 | std::uint32_t(bytes[at + 1]) << 16 | std::uint32_t(bytes[at + 2]) << 8 | bytes[at + 3]; };
    const std::uint32_t pw = be32(16), ph = be32(20);
    if (pw > std::uint32_t(limits.max_image_side) || ph > std::uint32_t(limits.max_image_side) ||
        std::uint64_t(pw) * ph > limits.max_image_texels) {
      ctx.problems[index] = "it is " + std::to_string(pw) + "x" + std::to_string(ph) + ", more than the loader accepts (" +
                            std::to_string(limits.max_image_side) + " a side, " + std::to_string(limits.max_image_texels) + " texels)";
      return true;
    }
  }
  if (size <= 0 || !stbi_info_from_memory(bytes, size, &w, &h, &channels)) {
    const char* why = stbi_failure_reason();
    ctx.problems[index] = std::string("not an image stb_image can read (") + (why ? why : "unknown format") + ")";
    return true;
  }
  if (w <= 0 || h <= 0 || w > limits.max_image_side || h > limits.max_image_side ||
      std::size_t(w) * std::size_t(h) > limits.max_image_texels) {
    ctx.problems[index] = "it is " + std::to_string(w) + "x" + std::to_string(h) + ", more than the loader accepts (" +
                          std::to_string(limits.max_image_side) + " a side, " +
                          std::to_string(limits.max_image_texels) + " texels)";
    return true;
  }
  const std::size_t texels = std::size_t(w) * std::size_t(h);
  if (texels > limits.max_total_texels - std::min(limits.max_total_texels, ctx.total_texels)) {
    ctx.problems[index] = "it is " + std::to_string(w) + "x" + std::to_string(h) + ", and with the scene's other images (" +
                          std::to_string(ctx.total_texels) + " texels) that is more than the loader accepts in all (" +
                          std::to_string(limits.max_total_texels) + " texels, each distinct image counted once)";
    return true;
  }
  ctx.total_texels += texels;
  bool sixteen = stbi_is_16_bit_from_memory(bytes, size);
  stbi_uc* pixels = stbi_load_from_memory(bytes, size, &w, &h, &channels, 4);  // 16-bit: converted to 8
  if (!pixels) {
    const char* why = stbi_failure_reason();
    ctx.problems[index] = std::string("it cannot be decoded (") + (why ? why : "corrupt") + ")";
    return true;
  }
  if (sixteen) ctx.converted.push_back(name);
  image->width = w;
  image->height = h;
  image->component = 4;
  image->bits = 8;
  image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  image->image.assign(pixels, pixels + std::size_t(w) * std::size_t(h) * 4);
  stbi_image_free(pixels);
  return true;
}

// tinygltf turns JSON into its own values recursively: a file of a million '[' overflows the
// stack. Nesting deeper than any real glTF (a few levels; extras a few more) is refused first.
constexpr int kMaxJsonDepth = 256;
bool json_too_deep(const unsigned char* text, std::size_t size) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < size; ++i) {
    unsigned char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') in_string = true;
    else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth) return true;
    } else if (c == ']' || c == '}') --depth;
  }
  return false;
}

// Extensions whose meaning we implement (or that change nothing we read): a file may require these.
const std::set<std::string>& supported_extensions() {
  static const std::set<std::string> s = {"KHR_lights_punctual", "KHR_materials_specular", "KHR_materials_emissive_strength",
                                          "KHR_texture_transform", "KHR_mesh_quantization"};
  return s;
}

// Index accessors without a bufferView, taken out of the JSON before tinygltf sees them:
// (glTF mesh, primitive) -> the accessor. glTF allows an accessor without one (all zeros);
// tinygltf refuses it where it holds indices.
using IndexFixups = std::map<std::pair<int, int>, int>;

// Reads the JSON before tinygltf does, for what tinygltf gets wrong first: a compressed mesh's
// accessors have no bufferView (Draco) or its buffer no data (meshopt's fallback), and tinygltf
// fails on those with a message of its own before extensionsRequired could name the
// extension. JSON that does not parse is left to tinygltf, which says where. `glb`: the whole
// .glb when the JSON came from one, rebuilt around the new JSON when it changes.
IndexFixups check_before_tinygltf(const unsigned char* text, std::size_t size, const fs::path& path,
                                  const std::vector<unsigned char>* glb, std::vector<unsigned char>& rewritten) {
  IndexFixups fixups;
  nlohmann::json doc = nlohmann::json::parse(text, text + size, nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) return fixups;
  if (auto it = doc.find("extensionsRequired"); it != doc.end() && it->is_array())
    for (const auto& e : *it)
      if (e.is_string() && !supported_extensions().count(e.get<std::string>()))
        throw Error("cannot load scene '" + path.string() + "': it requires the extension " + e.get<std::string>() +
                    ", which lightpass does not support" +
                    (e == "KHR_draco_mesh_compression" || e == "EXT_meshopt_compression" || e == "KHR_meshopt_compression"
                         ? " (a compressed mesh: export it uncompressed)"
                         : ""));
  auto accessors = doc.find("accessors");
  auto meshes = doc.find("meshes");
  if (accessors == doc.end() || !accessors->is_array() || meshes == doc.end() || !meshes->is_array()) return fixups;
  for (std::size_t m = 0; m < meshes->size(); ++m) {
    auto& mesh = (*meshes)[m];
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    auto& prims = mesh["primitives"];
    for (std::size_t p = 0; p < prims.size(); ++p) {
      auto& prim = prims[p];
      if (!prim.is_object() || !prim.contains("indices") || !prim["indices"].is_number_unsigned()) continue;
      const std::uint64_t a = prim["indices"].get<std::uint64_t>();
      if (a >= accessors->size() || !(*accessors)[a].is_object() || (*accessors)[a].contains("bufferView")) continue;
      fixups[{int(m), int(p)}] = int(a);
      prim.erase("indices");
    }
  }
  if (fixups.empty()) return fixups;
  std::string json = doc.dump();
  if (!glb) {
    rewritten.assign(json.begin(), json.end());
    return fixups;
  }
  // A .glb: header (magic, version, length), the JSON chunk (padded with spaces), the rest as it was.
  while (json.size() % 4) json += ' ';
  std::uint32_t old_json = 0;
  std::memcpy(&old_json, glb->data() + 12, 4);
  const std::size_t rest = std::min<std::size_t>(glb->size(), 20 + std::size_t(old_json));
  const std::size_t total = 20 + json.size() + (glb->size() - rest);
  if (total > std::numeric_limits<std::uint32_t>::max()) return {};
  auto u32 = [&](std::uint32_t v) { for (int i = 0; i < 4; ++i) rewritten.push_back(static_cast<unsigned char>(v >> (8 * i))); };
  rewritten.assign(glb->begin(), glb->begin() + 8);
  u32(static_cast<std::uint32_t>(total));
  u32(static_cast<std::uint32_t>(json.size()));
  u32(0x4E4F534Au);  // "JSON"
  rewritten.insert(rewritten.end(), json.begin(), json.end());
  rewritten.insert(rewritten.end(), glb->begin() + std::ptrdiff_t(rest), glb->end());
  return fixups;
}

// Reads accessor elements as floats (or as indices), checking every byte it touches, so a
// malformed file becomes an error message rather than an out-of-bounds read.
class AccessorReader {
 public:
  AccessorReader(const tinygltf::Model& m, int index, const std::string& where) : where_(where) {
    std::string name = "accessor " + std::to_string(index);
    if (index < 0 || index >= static_cast<int>(m.accessors.size())) fail(name + " does not exist");
    acc_ = &m.accessors[index];
    if (acc_->sparse.isSparse) fail(name + " is sparse; sparse accessors are not supported");
    components_ = tinygltf::GetNumComponentsInType(acc_->type);
    component_bytes_ = tinygltf::GetComponentSizeInBytes(acc_->componentType);
    if (components_ <= 0 || component_bytes_ <= 0) fail(name + " has an unknown type");
    name_ = name;
    // glTF: an accessor without a bufferView holds zeros (data_ stays null).
    if (acc_->bufferView < 0) return;
    if (acc_->bufferView >= static_cast<int>(m.bufferViews.size()))
      fail(name + ": its bufferView " + std::to_string(acc_->bufferView) + " does not exist");
    const auto& view = m.bufferViews[acc_->bufferView];
    if (view.buffer < 0 || view.buffer >= static_cast<int>(m.buffers.size()))
      fail(name + ": buffer view " + std::to_string(acc_->bufferView) + " has no buffer");
    const auto& buffer = m.buffers[view.buffer];
    const std::size_t elem = std::size_t(components_) * std::size_t(component_bytes_);
    stride_ = view.byteStride ? view.byteStride : elem;
    if (stride_ < elem)
      fail(name + ": byteStride " + std::to_string(stride_) + " is less than one element (" + std::to_string(elem) + " bytes)");
    // The view inside the buffer, the accessor inside the view: offset + stride (count - 1) + element.
    std::size_t view_end = 0, last = 0, need = 0;
    bool ok = add(view.byteOffset, view.byteLength, view_end) && view_end <= buffer.data.size();
    if (ok && acc_->count > 0)
      ok = mul(stride_, acc_->count - 1, last) && add(acc_->byteOffset, last, need) && add(need, elem, need) && need <= view.byteLength;
    else if (ok)
      ok = acc_->byteOffset <= view.byteLength;
    if (!ok)
      fail(name + " (" + std::to_string(acc_->count) + " elements of " + std::to_string(elem) + " bytes, stride " +
           std::to_string(stride_) + ", offset " + std::to_string(acc_->byteOffset) + ") reads past the end of buffer view " +
           std::to_string(acc_->bufferView) + " or its buffer ('" + buffer.uri.substr(0, 64) + "', " +
           std::to_string(buffer.data.size()) + " bytes)");
    data_ = buffer.data.data() + view.byteOffset + acc_->byteOffset;
  }
  size_t count() const { return acc_->count; }
  int components() const { return components_; }
  const std::string& name() const { return name_; }

  int type() const { return acc_->type; }
  bool zeros() const { return data_ == nullptr; }  // no bufferView: every element is 0

  float component(size_t i, int c) const {
    if (!data_) return 0;
    const unsigned char* p = data_ + i * stride_ + std::size_t(c) * std::size_t(component_bytes_);
    switch (acc_->componentType) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); return f; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return acc_->normalized ? *p / 255.f : *p;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t v; std::memcpy(&v, p, 2); return acc_->normalized ? v / 65535.f : v; }
      case TINYGLTF_COMPONENT_TYPE_BYTE: { auto v = static_cast<std::int8_t>(*p); return acc_->normalized ? std::max(v / 127.f, -1.f) : v; }
      case TINYGLTF_COMPONENT_TYPE_SHORT: {
        std::int16_t v; std::memcpy(&v, p, 2); return acc_->normalized ? std::max(v / 32767.f, -1.f) : v; }
      default: fail(name_ + ": unsupported component type for a vertex attribute");
    }
  }
  std::uint32_t index(size_t i) const {
    if (!data_) {
      if (acc_->componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && acc_->componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
          acc_->componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        fail(name_ + ": indices must be unsigned byte, short or int");
      return 0;
    }
    const unsigned char* p = data_ + i * stride_;
    switch (acc_->componentType) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return *p;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { std::uint16_t v; std::memcpy(&v, p, 2); return v; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { std::uint32_t v; std::memcpy(&v, p, 4); return v; }
      default: fail(name_ + ": indices must be unsigned byte, short or int");
    }
  }
  template <int N>
  glm::vec<N, float> vec(size_t i) const {
    glm::vec<N, float> v(0);
    for (int c = 0; c < std::min(N, components_); ++c) v[c] = component(i, c);
    if (!finite(v)) fail(name_ + " holds a number that is not finite (element " + std::to_string(i) + ")");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw Error(where_ + ": " + what); }
  const tinygltf::Accessor* acc_ = nullptr;
  const unsigned char* data_ = nullptr;
  int components_ = 0, component_bytes_ = 0;
  size_t stride_ = 0;
  std::string where_, name_;
};

glm::vec3 vec3_or(const std::vector<double>& v, glm::vec3 fallback) {
  return v.size() >= 3 ? glm::vec3(v[0], v[1], v[2]) : fallback;
}

ImageRGBA8 fallback_checker(glm::u8vec4 a, glm::u8vec4 b) {
  ImageRGBA8 img;
  img.width = img.height = 8;
  img.pixels.resize(8 * 8 * 4);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      glm::u8vec4 c = ((x ^ y) & 1) ? a : b;
      std::memcpy(img.at(x, y), &c, 4);
    }
  return img;
}

// tinygltf's JSON value as nlohmann::json (tinygltf keeps extras in its own type).
nlohmann::json json_text(const tinygltf::Value& v) {
  if (v.IsBool()) return v.Get<bool>();
  if (v.IsInt()) return v.Get<int>();
  if (v.IsNumber()) return v.GetNumberAsDouble();
  if (v.IsString()) return v.Get<std::string>();
  if (v.IsArray()) {
    nlohmann::json a = nlohmann::json::array();
    for (size_t i = 0; i < v.ArrayLen(); ++i) a.push_back(json_text(v.Get(static_cast<int>(i))));
    return a;
  }
  if (v.IsObject()) {
    nlohmann::json o = nlohmann::json::object();
    for (const auto& key : v.Keys()) o[key] = json_text(v.Get(key));
    return o;
  }
  return nullptr;
}

// KHR_texture_transform of one texture: uv' = T(offset) R(rotation) S(scale) uv.
struct UvTransform {
  glm::vec2 offset{0}, scale{1};
  float rotation = 0;
  bool identity() const { return offset == glm::vec2(0) && scale == glm::vec2(1) && rotation == 0; }
  bool operator==(const UvTransform&) const = default;
  glm::vec2 apply(glm::vec2 uv) const {
    glm::vec2 s = uv * scale;
    float c = std::cos(rotation), n = std::sin(rotation);
    return glm::vec2(c * s.x + n * s.y, -n * s.x + c * s.y) + offset;
  }
};

class Loader {
 public:
  Loader(const tinygltf::Model& m, Scene& s, const ImageContext& images, const FileContext& files, const SceneLimits& limits,
         const IndexFixups& fixups)
      : m_(m), s_(s), images_(images), files_(files), limits(limits), fixups_(fixups) {}

  void load() {
    note_unsupported_document();
    s_.materials.reserve(m_.materials.size() + 1);
    for (size_t i = 0; i < m_.materials.size(); ++i) s_.materials.push_back(material(m_.materials[i], int(i)));
    if (std::size_t blended = std::count_if(s_.materials.begin(), s_.materials.end(), [](const Material& m) { return m.blend; }))
      s_.notes.push_back(std::to_string(blended) + " material(s) with alphaMode BLEND: chapter 10 draws them blended over the "
                         "image; the deferred G-buffer (chapters 02-09) leaves them out, chapter 01 draws them opaque");
    default_material_ = static_cast<int>(s_.materials.size());
    s_.materials.push_back(Material{.name = "default", .base_color = glm::vec4(0.8f, 0.8f, 0.8f, 1), .specular_color = glm::vec3(0.04f)});
    uv_transform_.resize(s_.materials.size());
    for (size_t i = 0; i < m_.materials.size(); ++i) uv_transform_[i] = material_uv_transform(m_.materials[i], int(i));
    mesh_of_gltf_.assign(m_.meshes.size(), -1);

    int scene_index = m_.defaultScene >= 0 ? m_.defaultScene : 0;
    if (m_.scenes.empty()) throw Error(file() + ": the file has no scene");
    if (scene_index >= static_cast<int>(m_.scenes.size())) throw Error(file() + ": default scene does not exist");
    const auto& scene = m_.scenes[scene_index];
    if (scene.extras.Has("lightpass")) {
      const auto& lp = scene.extras.Get("lightpass");
      if (lp.Has("ambient")) s_.ambient = number3(lp.Get("ambient"), glm::vec3(0));
      s_.lightpass_json = json_text(lp).dump();
      if (!finite(s_.ambient) || glm::any(glm::lessThan(s_.ambient, glm::vec3(0))))
        throw Error(file() + ": the scene's extras.lightpass.ambient must be three finite numbers >= 0");
    }
    check_expansion(scene.nodes);
    for (int root : scene.nodes) visit(root, glm::mat4(1), 0);
    // Triangles, not primitives: a primitive of no indices, or of triangles that all have zero
    // area (every POSITION the same), draws nothing, and a blank image must not pass silently.
    std::vector<std::optional<std::pair<std::size_t, std::size_t>>> counted(s_.meshes.size());
    std::size_t triangles = zero_area_triangles_, with_area = 0;
    for (const auto& inst : s_.instances) {
      auto& c = counted[std::size_t(inst.mesh)];
      if (!c) c = triangle_counts(s_.meshes[std::size_t(inst.mesh)]);
      triangles += c->first;
      with_area += c->second;
    }
    if (with_area == 0) {
      std::string why = skipped_primitives_ ? " (" + std::to_string(skipped_primitives_) + " primitives are points or lines, which are skipped)" : "";
      if (triangles > 0) why = " (its " + std::to_string(triangles) + " triangles all have zero area: their corners coincide or lie on a line)";
      throw Error(file() + ": the scene has no triangles to draw" + why);
    }
    compute_bounds();
    rebase_far_scene();
    rescale_extreme_scene();
    usable_depth_ranges();
    drop_lights_of_no_range();
    bound_light_work();
    add_auto_view();
    add_default_lights();
    report_unsupported();
  }

 private:
  std::string file() const { return s_.path.string(); }

  static glm::vec3 number3(const tinygltf::Value& v, glm::vec3 fallback) {
    if (!v.IsArray() || v.ArrayLen() < 3) return fallback;
    glm::vec3 r;
    for (int i = 0; i < 3; ++i) r[i] = static_cast<float>(v.Get(i).GetNumberAsDouble());
    return r;
  }

  // A mesh's triangles, and those of them with an area (in the mesh's own space).
  std::pair<std::size_t, std::size_t> triangle_counts(const Mesh& mesh) const {
    std::size_t all = 0, area = 0;
    for (const auto& p : mesh.primitives)
      for (std::uint32_t t = p.first_index; t + 2 < p.first_index + p.index_count; t += 3) {
        // In double: a model a few 1e-20 m across has areas that underflow a float.
        const glm::dvec3 a = s_.vertices[s_.indices[t]].position, b = s_.vertices[s_.indices[t + 1]].position,
                         c = s_.vertices[s_.indices[t + 2]].position;
        ++all;
        area += glm::any(glm::notEqual(glm::cross(b - a, c - a), glm::dvec3(0)));
      }
    return {all, area};
  }

  // What the file uses and lightpass does not do, said once for the whole file.
  void unsupported(const std::string& feature) { ++unsupported_[feature]; }
  void unsupported_once(const std::string& feature) { unsupported_[feature] = 1; }
  void note_unsupported_document() {
    for (const auto& e : m_.extensionsUsed)
      if (!supported_extensions().count(e)) unsupported_once("extension " + e);
    if (!m_.animations.empty()) unsupported_["animations (the scene is shown at rest)"] = int(m_.animations.size());
    if (!m_.skins.empty()) unsupported_["skins (drawn in the bind pose)"] = int(m_.skins.size());
    for (const auto& s : m_.samplers) {
      bool ours = (s.wrapS == TINYGLTF_TEXTURE_WRAP_REPEAT && s.wrapT == TINYGLTF_TEXTURE_WRAP_REPEAT) &&
                  (s.minFilter == -1 || s.minFilter == TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR) &&
                  (s.magFilter == -1 || s.magFilter == TINYGLTF_TEXTURE_FILTER_LINEAR);
      if (!ours) unsupported("sampler wrap/filter modes (textures always repeat, trilinear)");
    }
  }
  void report_unsupported() {
    if (!images_.converted.empty()) {
      std::string names;
      for (size_t i = 0; i < images_.converted.size() && i < 3; ++i) names += (i ? ", '" : "'") + images_.converted[i] + "'";
      if (images_.converted.size() > 3) names += ", ...";
      unsupported_["16-bit images read as 8 bits per channel: " + names] += 0;
    }
    if (unsupported_.empty()) return;
    std::string text = s_.path.filename().string() + " uses what lightpass does not support; ignored or converted:";
    bool first = true;
    for (const auto& [feature, count] : unsupported_) {
      text += std::string(first ? " " : "; ") + feature + (count > 1 ? " (x" + std::to_string(count) + ")" : "");
      first = false;
    }
    warn(text);
  }

  int texture(int gltf_index, bool srgb, const std::string& material_name) {
    if (gltf_index < 0) return -1;
    auto key = std::make_pair(gltf_index, srgb);
    if (auto it = texture_of_key_.find(key); it != texture_of_key_.end()) return it->second;
    Texture t;
    t.srgb = srgb;
    const tinygltf::Image* img = nullptr;
    int source = -1;
    if (gltf_index < static_cast<int>(m_.textures.size())) {
      source = m_.textures[gltf_index].source;
      if (auto same = images_.same_as.find(source); same != images_.same_as.end()) source = same->second;
      if (source >= 0 && source < static_cast<int>(m_.images.size())) img = &m_.images[source];
    }
    // Textures of one image (or of images of the same bytes) share one Scene texture.
    if (img) {
      key = std::make_pair(-1 - source, srgb);
      if (auto it = texture_of_key_.find(key); it != texture_of_key_.end()) return texture_of_key_[std::make_pair(gltf_index, srgb)] = it->second;
    }
    t.name = img ? (img->uri.empty() ? (img->name.empty() ? "image " + std::to_string(source) : img->name) : img->uri)
                 : "texture " + std::to_string(gltf_index);
    std::size_t texels = img && img->width > 0 && img->height > 0 ? std::size_t(img->width) * std::size_t(img->height) : 0;
    if (img && texels > 0 && img->bits == 8 && img->component >= 1 && img->component <= 4 &&
        img->image.size() >= texels * std::size_t(img->component)) {
      t.image.width = img->width;
      t.image.height = img->height;
      t.image.pixels.resize(texels * 4);
      for (size_t p = 0; p < texels; ++p)
        for (int c = 0; c < 4; ++c)
          t.image.pixels[p * 4 + c] = c < img->component ? img->image[p * img->component + c]
                                                        : (c == 3 ? 255 : img->image[p * img->component]);
    } else {
      // Magenta checker for colours (impossible to miss), flat normal for normal maps.
      t.image = srgb ? fallback_checker({255, 0, 255, 255}, {32, 32, 32, 255})
                     : fallback_checker({128, 128, 255, 255}, {128, 128, 255, 255});
      t.fallback = true;
      std::string why;
      if (!img) why = "texture " + std::to_string(gltf_index) + " has no image";
      else if (auto it = images_.problems.find(source); it != images_.problems.end()) why = it->second;
      else if (!img->uri.empty()) {
        why = (s_.path.parent_path() / img->uri).string();
        for (const auto& p : files_.problems)
          if (p.find(img->uri) != std::string::npos) why = p;
      } else why = "no image data";
      warn("material '" + material_name + "': texture '" + t.name + "' could not be loaded (" + why + "): using a fallback " +
           (srgb ? "checker" : "flat normal map"));
    }
    texture_of_key_[key] = texture_of_key_[std::make_pair(gltf_index, srgb)] = static_cast<int>(s_.textures.size());
    s_.textures.push_back(std::move(t));
    return static_cast<int>(s_.textures.size() - 1);
  }

  static UvTransform uv_transform(const tinygltf::ExtensionMap& extensions, int& tex_coord) {
    UvTransform t;
    auto it = extensions.find("KHR_texture_transform");
    if (it == extensions.end()) return t;
    const auto& e = it->second;
    auto pair = [&](const char* key, glm::vec2 fallback) {
      if (!e.Has(key) || !e.Get(key).IsArray() || e.Get(key).ArrayLen() < 2) return fallback;
      return glm::vec2(e.Get(key).Get(0).GetNumberAsDouble(), e.Get(key).Get(1).GetNumberAsDouble());
    };
    t.offset = pair("offset", glm::vec2(0));
    t.scale = pair("scale", glm::vec2(1));
    if (e.Has("rotation")) t.rotation = static_cast<float>(e.Get("rotation").GetNumberAsDouble());
    if (e.Has("texCoord")) tex_coord = e.Get("texCoord").GetNumberAsInt();
    return t;
  }

  // One transform per material (the vertices of a primitive carry one set of UVs): the base
  // colour's, else the normal map's, else the emissive texture's. Others that differ are named.
  UvTransform material_uv_transform(const tinygltf::Material& gm, int index) {
    const std::string name = material_label(gm, index);
    struct Slot { const char* what; int texture; int tex_coord; const tinygltf::ExtensionMap* ext; };
    const Slot slots[] = {{"baseColorTexture", gm.pbrMetallicRoughness.baseColorTexture.index, gm.pbrMetallicRoughness.baseColorTexture.texCoord,
                           &gm.pbrMetallicRoughness.baseColorTexture.extensions},
                          {"normalTexture", gm.normalTexture.index, gm.normalTexture.texCoord, &gm.normalTexture.extensions},
                          {"emissiveTexture", gm.emissiveTexture.index, gm.emissiveTexture.texCoord, &gm.emissiveTexture.extensions}};
    bool chosen = false;
    UvTransform out;
    for (const auto& s : slots) {
      if (s.texture < 0) continue;
      int tex_coord = s.tex_coord;
      UvTransform t = uv_transform(*s.ext, tex_coord);
      if (tex_coord != 0) unsupported("texCoord " + std::to_string(tex_coord) + " (TEXCOORD_0 is used)");
      if (!finite(t.offset) || !finite(t.scale) || !finite(t.rotation))
        throw Error(file() + ": material '" + name + "': KHR_texture_transform of its " + s.what + " is not finite");
      if (!chosen) {
        out = t;
        chosen = true;
      } else if (!(t == out)) {
        unsupported(std::string("a KHR_texture_transform of ") + s.what + " that differs from the material's first texture's (material '" + name + "')");
      }
    }
    return out;
  }

  static std::string material_label(const tinygltf::Material& gm, int index) {
    return gm.name.empty() ? "material" + std::to_string(index) : gm.name;
  }

  Material material(const tinygltf::Material& gm, int index) {
    Material mat;
    mat.name = gm.name;
    const std::string label = material_label(gm, index);
    const auto& pbr = gm.pbrMetallicRoughness;
    if (pbr.baseColorFactor.size() == 4)
      mat.base_color = glm::vec4(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2], pbr.baseColorFactor[3]);
    mat.base_color_texture = texture(pbr.baseColorTexture.index, true, gm.name);
    mat.roughness = static_cast<float>(pbr.roughnessFactor);
    mat.emissive = vec3_or(gm.emissiveFactor, glm::vec3(0));
    if (auto it = gm.extensions.find("KHR_materials_emissive_strength"); it != gm.extensions.end() && it->second.Has("emissiveStrength"))
      mat.emissive *= static_cast<float>(it->second.Get("emissiveStrength").GetNumberAsDouble());
    mat.emissive_texture = texture(gm.emissiveTexture.index, true, gm.name);
    mat.normal_texture = texture(gm.normalTexture.index, false, gm.name);
    mat.normal_scale = static_cast<float>(gm.normalTexture.scale);
    // Without KHR_materials_specular, glTF's dielectric reflectance at normal incidence (0.04).
    mat.specular_color = glm::vec3(0.04f);
    if (auto it = gm.extensions.find("KHR_materials_specular"); it != gm.extensions.end()) {
      const auto& e = it->second;
      mat.has_specular_extension = true;
      mat.specular_factor = e.Has("specularFactor") ? static_cast<float>(e.Get("specularFactor").GetNumberAsDouble()) : 1.f;
      glm::vec3 colour = e.Has("specularColorFactor") ? number3(e.Get("specularColorFactor"), glm::vec3(1)) : glm::vec3(1);
      mat.specular_color = colour * mat.specular_factor;
      if (e.Has("specularTexture") || e.Has("specularColorTexture")) unsupported("KHR_materials_specular textures (the factors are used)");
    }
    for (const auto& [name, value] : gm.extensions)
      if (!supported_extensions().count(name)) unsupported_once("extension " + name);
    if (pbr.metallicRoughnessTexture.index >= 0) unsupported("metallicRoughnessTexture (the roughness factor is used)");
    if (gm.occlusionTexture.index >= 0) unsupported("occlusionTexture");
    mat.blend = gm.alphaMode == "BLEND";
    if (gm.alphaMode != "OPAQUE" && gm.alphaMode != "BLEND" && !gm.alphaMode.empty())
      unsupported("alphaMode " + gm.alphaMode + " (drawn opaque)");
    mat.double_sided = gm.doubleSided;
    auto bad = [&](const char* what) { throw Error(file() + ": material '" + label + "': " + what + " must be finite and >= 0"); };
    if (!finite(mat.base_color) || glm::any(glm::lessThan(mat.base_color, glm::vec4(0)))) bad("baseColorFactor");
    if (!finite(mat.emissive) || glm::any(glm::lessThan(mat.emissive, glm::vec3(0)))) bad("emissiveFactor (times emissiveStrength)");
    if (!finite(mat.specular_color) || glm::any(glm::lessThan(mat.specular_color, glm::vec3(0)))) bad("the specular colour");
    if (!finite(mat.roughness) || mat.roughness < 0) bad("roughnessFactor");
    if (!finite(mat.normal_scale)) bad("normalTexture.scale");
    // Finite but past what a surface reflects (glTF: baseColorFactor in [0, 1]; the specular
    // extension clamps its reflectance to 1): the chapters' light cut-offs divide by the
    // largest reflectance, and 3e38 leaves them nothing. Clamped, the material named.
    auto clamp_to_one = [&](auto& colour, const char* what) {
      using V = std::remove_cvref_t<decltype(colour)>;
      if (!glm::any(glm::greaterThan(colour, V(1)))) return;
      std::string was;
      for (int i = 0; i < colour.length(); ++i) was += (i ? ", " : "") + number_text(colour[i]);
      warn("material '" + label + "': " + what + " (" + was + ") reflects more than all the light: clamped to 1");
      colour = glm::min(colour, V(1));
    };
    clamp_to_one(mat.base_color, "baseColorFactor");
    clamp_to_one(mat.specular_color, "the specular colour (specularColorFactor times specularFactor)");
    return mat;
  }

  glm::mat4 local_matrix(const tinygltf::Node& n, const std::string& name) {
    glm::mat4 m(1);
    if (n.matrix.size() == 16) {
      for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = static_cast<float>(n.matrix[i]);
    } else {
      glm::mat4 t = glm::translate(glm::mat4(1), vec3_or(n.translation, glm::vec3(0)));
      glm::quat q(1, 0, 0, 0);
      if (n.rotation.size() == 4) {
        q = glm::quat(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]), float(n.rotation[2]));
        float len = glm::length(q);
        if (!(len > 1e-6f) || !std::isfinite(len)) throw Error(file() + ": node '" + name + "': its rotation is not a unit quaternion (length " + number_text(len) + ")");
        if (std::abs(len - 1.f) > 1e-3f) q /= len;  // glTF requires unit quaternions; tolerate sloppy writers
      }
      glm::mat4 s = glm::scale(glm::mat4(1), vec3_or(n.scale, glm::vec3(1)));
      m = t * glm::mat4_cast(q) * s;
    }
    if (!finite(m)) throw Error(file() + ": node '" + name + "': its transform holds a number that is not finite");
    return m;
  }

  // What the node graph expands to, counted without expanding it (a child listed by k parents
  // counts k times), saturating: a DAG past the limits is refused before any work is done.
  void check_expansion(const std::vector<int>& roots) {
    struct Expansion { std::uint64_t visits = 0, instances = 0, lights = 0, cameras = 0; };
    constexpr std::uint64_t kCap = std::uint64_t(1) << 62;
    auto sum = [&](Expansion& a, const Expansion& b) {
      a.visits = std::min(kCap, a.visits + b.visits);
      a.instances = std::min(kCap, a.instances + b.instances);
      a.lights = std::min(kCap, a.lights + b.lights);
      a.cameras = std::min(kCap, a.cameras + b.cameras);
    };
    std::vector<std::optional<Expansion>> memo(m_.nodes.size());
    std::vector<char> on_path(m_.nodes.size(), 0);
    std::function<Expansion(int, int)> count = [&](int n, int depth) -> Expansion {
      if (n < 0 || n >= static_cast<int>(m_.nodes.size())) throw Error(file() + ": node " + std::to_string(n) + " does not exist");
      if (depth > 64 || on_path[n]) throw Error(file() + ": the node hierarchy is deeper than 64 (a cycle?)");
      if (memo[n]) return *memo[n];
      const auto& node = m_.nodes[n];
      auto light = node.extensions.find("KHR_lights_punctual");
      Expansion e{1, node.mesh >= 0, light != node.extensions.end() && light->second.Has("light"), node.camera >= 0};
      on_path[n] = 1;
      for (int child : node.children) sum(e, count(child, depth + 1));
      on_path[n] = 0;
      memo[n] = e;
      return e;
    };
    Expansion total;
    for (int root : roots) sum(total, count(root, 0));
    auto refuse = [&](std::uint64_t n, std::size_t limit, const std::string& what) {
      if (n > limit)
        throw Error(file() + ": more than " + std::to_string(limit) + " " + what + " (nodes shared as children of many parents?); the loader stops there");
    };
    refuse(total.instances, limits.max_instances, "mesh instances");
    refuse(total.lights, limits.max_lights, "lights");
    refuse(total.cameras, limits.max_cameras, "cameras");
    if (total.visits > limits.max_node_visits)
      throw Error(file() + ": the node hierarchy expands to more than " + std::to_string(limits.max_node_visits) +
                  " nodes (children shared by many parents); the loader stops there");
  }

  void visit(int node_index, const glm::mat4& parent, int depth) {
    if (node_index < 0 || node_index >= static_cast<int>(m_.nodes.size()))
      throw Error(file() + ": node " + std::to_string(node_index) + " does not exist");
    if (depth > 64) throw Error(file() + ": the node hierarchy is deeper than 64 (a cycle?)");
    // Nodes that list the same children share them: a small file can expand to 2^64 nodes.
    if (++visits_ > limits.max_node_visits)
      throw Error(file() + ": the node hierarchy expands to more than " + std::to_string(limits.max_node_visits) +
                  " nodes (children shared by many parents); the loader stops there");
    const auto& node = m_.nodes[node_index];
    auto label = [&] { return node.name.empty() ? "node" + std::to_string(node_index) : node.name; };
    if (local_.empty()) local_.resize(m_.nodes.size());
    if (!local_[node_index]) local_[node_index] = local_matrix(node, label());
    glm::mat4 world = parent * *local_[node_index];
    if (!finite(world)) throw Error(file() + ": node '" + label() + "': its world transform is not finite");
    const bool named = node.mesh >= 0 || node.camera >= 0 || node.extras.Has("lightpass") || !node.extensions.empty();
    if (!named) {
      for (int child : node.children) visit(child, world, depth + 1);
      return;
    }
    const std::string name = label();
    // What each visit copies is bounded too: a long name or big extras on a shared node.
    std::size_t copied = name.size() * (1 + (node.mesh >= 0) + (node.camera >= 0) + node.extras.Has("lightpass"));
    if ((copied_bytes_ += copied) > limits.max_name_bytes)
      throw Error(file() + ": the node names and extras would take more than " + std::to_string(limits.max_name_bytes >> 20) +
                  " MiB (nodes shared by many parents?); the loader stops there");
    if (node.mesh >= 0) add_instance(node, name, world);
    if (node.camera >= 0) add_camera(node, name, world);
    if (node.extras.Has("lightpass")) {
      if (s_.node_extras.size() >= limits.max_node_extras)
        throw Error(file() + ": more than " + std::to_string(limits.max_node_extras) + " nodes with extras.lightpass; the loader stops there");
      if (extras_json_.empty()) extras_json_.resize(m_.nodes.size());
      if (!extras_json_[node_index]) extras_json_[node_index] = json_text(node.extras.Get("lightpass")).dump();
      if ((copied_bytes_ += extras_json_[node_index]->size()) > limits.max_name_bytes)
        throw Error(file() + ": the nodes' extras would take more than " + std::to_string(limits.max_name_bytes >> 20) + " MiB; the loader stops there");
      s_.node_extras.push_back({.name = name, .world = world, .lightpass_json = *extras_json_[node_index]});
    }
    if (auto it = node.extensions.find("KHR_lights_punctual"); it != node.extensions.end() && it->second.Has("light"))
      add_light(it->second.Get("light").GetNumberAsInt(), name, world, node);
    for (int child : node.children) visit(child, world, depth + 1);
  }

  void add_instance(const tinygltf::Node& node, const std::string& name, const glm::mat4& world) {
    if (node.mesh >= static_cast<int>(m_.meshes.size()))
      throw Error(file() + ": node '" + name + "' uses mesh " + std::to_string(node.mesh) + ", which does not exist");
    if (s_.instances.size() >= limits.max_instances)
      throw Error(file() + ": more than " + std::to_string(limits.max_instances) +
                  " mesh instances (nodes shared as children of many parents?); the loader stops there");
    if (mesh_of_gltf_[node.mesh] < 0) mesh_of_gltf_[node.mesh] = mesh(node.mesh);
    Instance inst{.name = name, .mesh = mesh_of_gltf_[node.mesh], .model = world};
    if (node.extras.Has("lightpass")) {
      const auto& e = node.extras.Get("lightpass");
      std::string shape = e.Has("shape") && e.Get("shape").IsString() ? e.Get("shape").Get<std::string>() : "";
      if (shape == "sphere" && e.Has("radius")) {
        inst.shape.kind = Shape::Sphere;
        inst.shape.radius = static_cast<float>(e.Get("radius").GetNumberAsDouble());
        if (!(inst.shape.radius > 0) || !finite(inst.shape.radius))
          throw Error(file() + ": node '" + name + "': extras.lightpass radius must be a finite number > 0");
      } else if (shape == "rect" && e.Has("size") && e.Get("size").IsArray() && e.Get("size").ArrayLen() == 2) {
        inst.shape.kind = Shape::Rect;
        inst.shape.size = {e.Get("size").Get(0).GetNumberAsDouble(), e.Get("size").Get(1).GetNumberAsDouble()};
        if (!finite(inst.shape.size) || !(inst.shape.size.x > 0) || !(inst.shape.size.y > 0))
          throw Error(file() + ": node '" + name + "': extras.lightpass size must be two finite numbers > 0");
      }
    }
    s_.instances.push_back(inst);
  }

  int mesh(int gltf_mesh) {
    const auto& gm = m_.meshes[gltf_mesh];
    Mesh out;
    out.name = gm.name.empty() ? "mesh" + std::to_string(gltf_mesh) : gm.name;
    for (size_t p = 0; p < gm.primitives.size(); ++p) {
      const auto& prim = gm.primitives[p];
      std::string where = s_.path.filename().string() + ": mesh '" + out.name + "' primitive " + std::to_string(p);
      int mode = prim.mode == -1 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
      if (mode < TINYGLTF_MODE_TRIANGLES) {
        static const char* kNames[] = {"points", "lines", "line loops", "line strips"};
        unsupported(std::string(mode >= 0 ? kNames[mode] : "primitives of an unknown mode") + " (skipped)");
        ++skipped_primitives_;
        continue;
      }
      if (mode > TINYGLTF_MODE_TRIANGLE_FAN) {
        unsupported("primitives of an unknown mode (skipped)");
        ++skipped_primitives_;
        continue;
      }
      auto fixed = fixups_.find({gltf_mesh, int(p)});
      Primitive drawn = primitive(prim, mode, where, fixed == fixups_.end() ? prim.indices : fixed->second);
      if (drawn.index_count > 0) out.primitives.push_back(drawn);  // none: nothing to draw
    }
    s_.meshes.push_back(std::move(out));
    return static_cast<int>(s_.meshes.size() - 1);
  }

  Primitive primitive(const tinygltf::Primitive& prim, int mode, const std::string& where, int indices) {
    auto attr = [&](const char* name) { auto it = prim.attributes.find(name); return it == prim.attributes.end() ? -1 : it->second; };
    for (const auto& [name, accessor] : prim.attributes)
      if (name != "POSITION" && name != "NORMAL" && name != "TEXCOORD_0" && name != "TANGENT")
        unsupported("vertex attribute " + (name.rfind("_") != std::string::npos && std::isdigit(static_cast<unsigned char>(name.back()))
                                               ? name.substr(0, name.rfind('_') + 1) + "n" : name));
    if (!prim.targets.empty()) unsupported("morph targets (the base shape is drawn)");
    if (prim.extensions.count("KHR_draco_mesh_compression")) unsupported_once("extension KHR_draco_mesh_compression");
    if (attr("POSITION") < 0) throw Error(where + ": no POSITION attribute");
    AccessorReader pos(m_, attr("POSITION"), where + " POSITION");
    require_type(pos, "POSITION", TINYGLTF_TYPE_VEC3, where);
    const size_t n = pos.count();
    if (n > limits.max_vertices - std::min(limits.max_vertices, s_.vertices.size()))
      throw Error(where + ": POSITION " + pos.name() + " has " + std::to_string(n) + " vertices; with the scene's " +
                  std::to_string(s_.vertices.size()) + " that is more than the loader accepts (" + std::to_string(limits.max_vertices) + ")");
    int material = prim.material >= 0 && prim.material < default_material_ ? prim.material : default_material_;
    // Zeros cost the file nothing (no bufferView): a POSITION or indices of zeros make only
    // triangles of no area, so they are counted as such, never expanded into memory.
    std::optional<std::size_t> zero_elements;
    if (pos.zeros()) zero_elements = n;
    if (indices >= 0) {
      AccessorReader idx(m_, indices, where + " indices");
      require_type(idx, "indices", TINYGLTF_TYPE_SCALAR, where);
      if (pos.zeros() || idx.zeros()) zero_elements = idx.count();
    }
    if (zero_elements) {
      const std::size_t e = *zero_elements;
      zero_area_triangles_ += mode == TINYGLTF_MODE_TRIANGLES ? e / 3 : e > 2 ? e - 2 : 0;
      return Primitive{.first_index = static_cast<std::uint32_t>(s_.indices.size()), .index_count = 0, .material = material};
    }
    std::vector<Vertex> verts(n);
    for (size_t i = 0; i < n; ++i) verts[i].position = pos.vec<3>(i);
    auto read = [&](const char* name, auto assign) {
      if (attr(name) < 0) return false;
      AccessorReader r(m_, attr(name), where + " " + name);
      require_type(r, name, std::string(name) == "TANGENT" ? TINYGLTF_TYPE_VEC4 : std::string(name) == "NORMAL" ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC2, where);
      if (r.count() != n) throw Error(where + ": " + name + " (" + r.name() + ") has " + std::to_string(r.count()) + " elements but POSITION has " + std::to_string(n));
      for (size_t i = 0; i < n; ++i) assign(verts[i], r, i);
      return true;
    };
    bool has_normal = read("NORMAL", [](Vertex& v, const AccessorReader& r, size_t i) {
      glm::vec3 normal = r.vec<3>(i);
      v.normal = glm::dot(normal, normal) > 0 ? glm::normalize(normal) : glm::vec3(0);  // zero: the shaders use the face's
    });
    bool has_uv = read("TEXCOORD_0", [](Vertex& v, const AccessorReader& r, size_t i) { v.uv = r.vec<2>(i); });
    bool has_tangent = read("TANGENT", [](Vertex& v, const AccessorReader& r, size_t i) { v.tangent = r.vec<4>(i); });

    // Indices of this primitive's own vertices, as triangles.
    std::vector<std::uint32_t> local;
    if (indices >= 0) {
      AccessorReader idx(m_, indices, where + " indices");
      require_type(idx, "indices", TINYGLTF_TYPE_SCALAR, where);
      if (idx.count() > limits.max_indices)
        throw Error(where + ": indices " + idx.name() + " has " + std::to_string(idx.count()) + " elements, more than the loader accepts (" +
                    std::to_string(limits.max_indices) + ")");
      local.resize(idx.count());
      for (size_t i = 0; i < idx.count(); ++i) {
        std::uint32_t k = idx.index(i);
        if (k >= n) throw Error(where + ": index " + std::to_string(k) + " (at position " + std::to_string(i) +
                                ") is past the " + std::to_string(n) + " vertices");
        local[i] = k;
      }
    } else {
      if (n > std::numeric_limits<std::uint32_t>::max()) throw Error(where + ": more than 2^32 vertices");
      local.resize(n);
      for (size_t i = 0; i < n; ++i) local[i] = static_cast<std::uint32_t>(i);
    }
    auto too_many = [&](std::size_t vertices, std::size_t indices) {
      // Checked before allocating: a strip triples its indices, un-indexing makes one vertex per index.
      if (vertices > limits.max_vertices - std::min(limits.max_vertices, s_.vertices.size()) ||
          indices > limits.max_indices - std::min(limits.max_indices, s_.indices.size()))
        throw Error(where + ": the scene would hold more than " + std::to_string(limits.max_vertices) + " vertices or " +
                    std::to_string(limits.max_indices) + " indices, more than the loader accepts");
    };
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN) {
      too_many(0, local.size() > 2 ? (local.size() - 2) * 3 : 0);
      local = to_triangles(local, mode);
    }
    too_many(has_normal ? n : local.size(), local.size());
    if (local.size() % 3) throw Error(where + ": " + std::to_string(local.size()) + " indices is not a whole number of triangles");

    if (has_uv && !uv_transform_[material].identity())
      for (auto& v : verts) v.uv = uv_transform_[material].apply(v.uv);
    if (!has_normal) {
      // glTF: "When normals are not specified, client implementations MUST calculate flat
      // normals": every triangle gets its own three vertices and its face normal.
      std::vector<Vertex> flat(local.size());
      for (size_t i = 0; i < local.size(); ++i) flat[i] = verts[local[i]];
      for (size_t t = 0; t + 2 < flat.size(); t += 3) {
        glm::vec3 face = glm::cross(flat[t + 1].position - flat[t].position, flat[t + 2].position - flat[t].position);
        float len = glm::length(face);
        face = len > 0 && std::isfinite(len) ? face / len : glm::vec3(0, 1, 0);
        for (int k = 0; k < 3; ++k) flat[t + k].normal = face;
      }
      verts = std::move(flat);
      for (size_t i = 0; i < local.size(); ++i) local[i] = static_cast<std::uint32_t>(i);
    }

    const std::size_t base = s_.vertices.size();
    s_.vertices.insert(s_.vertices.end(), verts.begin(), verts.end());
    Primitive out;
    out.first_index = static_cast<std::uint32_t>(s_.indices.size());
    s_.indices.reserve(s_.indices.size() + local.size());
    for (std::uint32_t k : local) s_.indices.push_back(static_cast<std::uint32_t>(base + k));
    out.index_count = static_cast<std::uint32_t>(local.size());
    out.material = material;
    if (!has_tangent) generate_tangents(s_.vertices, s_.indices, out.first_index, out.index_count, has_uv);
    return out;
  }

  // glTF fixes each attribute's type: a POSITION of VEC2 or SCALAR would read as points on a
  // plane or a line (nothing to see), so it is refused by name rather than drawn.
  void require_type(const AccessorReader& r, const std::string& what, int type, const std::string& where) const {
    if (r.type() == type) return;
    auto type_name = [](int t) -> std::string {
      switch (t) {
        case TINYGLTF_TYPE_SCALAR: return "SCALAR";
        case TINYGLTF_TYPE_VEC2: return "VEC2";
        case TINYGLTF_TYPE_VEC3: return "VEC3";
        case TINYGLTF_TYPE_VEC4: return "VEC4";
        case TINYGLTF_TYPE_MAT2: return "MAT2";
        case TINYGLTF_TYPE_MAT3: return "MAT3";
        case TINYGLTF_TYPE_MAT4: return "MAT4";
        default: return "type " + std::to_string(t);
      }
    };
    throw Error(where + ": " + what + " (" + r.name() + ") is " + type_name(r.type()) + "; glTF requires " + type_name(type));
  }

  // glTF 2.0 §3.7.2.1: strip triangle i is (i, i+1+i%2, i+2-i%2), fan triangle i (i+1, i+2, 0),
  // both keeping the winding of the first triangle.
  static std::vector<std::uint32_t> to_triangles(const std::vector<std::uint32_t>& in, int mode) {
    std::vector<std::uint32_t> out;
    if (in.size() < 3) return out;
    out.reserve((in.size() - 2) * 3);
    for (size_t i = 0; i + 2 < in.size(); ++i) {
      if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        out.push_back(in[i]);
        out.push_back(in[i + 1 + i % 2]);
        out.push_back(in[i + 2 - i % 2]);
      } else {
        out.push_back(in[i + 1]);
        out.push_back(in[i + 2]);
        out.push_back(in[0]);
      }
    }
    return out;
  }

  void add_camera(const tinygltf::Node& node, const std::string& name, const glm::mat4& world) {
    if (node.camera >= static_cast<int>(m_.cameras.size())) throw Error(file() + ": node '" + name + "' uses a camera that does not exist");
    const auto& c = m_.cameras[node.camera];
    if (s_.cameras.size() >= limits.max_cameras)
      throw Error(file() + ": more than " + std::to_string(limits.max_cameras) + " cameras; the loader stops there");
    if (c.type != "perspective") {
      unsupported(c.type + " cameras (skipped: only perspective cameras are views)");
      return;
    }
    const auto& p = c.perspective;
    auto bad = [&](const std::string& what) { throw Error(file() + ": camera '" + name + "': " + what); };
    if (!(p.yfov > 0 && p.yfov < std::numbers::pi)) bad("yfov " + number_text(p.yfov) + " is not between 0 and pi");
    if (!(p.znear > 0) || !std::isfinite(p.znear)) bad("znear " + number_text(p.znear) + " must be > 0");
    if (p.zfar != 0 && !(p.zfar > p.znear)) bad("zfar " + number_text(p.zfar) + " must be greater than znear " + number_text(p.znear));
    if (node.rotation.size() == 4 && node.rotation[0] == 0 && node.rotation[1] == 0 && node.rotation[2] == 0 && node.rotation[3] == 0)
      bad("its node's rotation is the zero quaternion");
    // The projection is built in float: a yfov below pi as a double can be pi as a float.
    if (!(float(p.yfov) < std::numbers::pi_v<float>)) {
      std::ostringstream y;
      y << std::setprecision(10) << p.yfov;
      bad("yfov " + y.str() + " is below pi, but rounds to pi as a float (the projection's number type)");
    }
    Camera cam{.name = name, .world = world, .yfov = float(p.yfov), .znear = float(p.znear),
               .zfar = p.zfar > 0 ? float(p.zfar) : std::max(1000.f, float(p.znear) * 1e4f)};
    if (!(cam.zfar > cam.znear) || !std::isfinite(cam.zfar)) bad("znear and zfar do not give a depth range in float");
    // Legal, but no image: near pi the scene shrinks to a speck in the middle (the depth range
    // is checked with the scene's bounds: usable_depth_ranges()).
    constexpr float kWidestYfov = 2.8f;  // 160 degrees
    if (cam.yfov > kWidestYfov) {
      warn("camera '" + name + "': yfov " + number_text(p.yfov) + " leaves the scene a speck in the middle of the image; using " +
           number_text(kWidestYfov) + " (160 degrees)");
      cam.yfov = kWidestYfov;
    }
    // Remove any scale from the node so view() is a rigid transform.
    for (int i = 0; i < 3; ++i) {
      glm::vec3 axis(cam.world[i]);
      float len = glm::length(axis);
      if (!(len > 1e-12f) || !std::isfinite(len)) bad("its node's transform has a zero (or non-finite) scale");
      cam.world[i] = glm::vec4(glm::normalize(axis), 0);  // (not axis / len: the same bits as before)
    }
    s_.cameras.push_back(cam);
  }

  void add_light(int index, const std::string& name, const glm::mat4& world, const tinygltf::Node& node) {
    if (index < 0 || index >= static_cast<int>(m_.lights.size()))
      throw Error(file() + ": node '" + name + "' uses light " + std::to_string(index) + ", which does not exist");
    ++lights_declared_;
    if (s_.lights.size() >= limits.max_lights)
      throw Error(file() + ": more than " + std::to_string(limits.max_lights) + " lights; the loader stops there");
    const auto& gl = m_.lights[index];
    Light l;
    l.name = gl.name.empty() ? name : gl.name;
    l.color = vec3_or(gl.color, glm::vec3(1));
    l.intensity = static_cast<float>(gl.intensity);
    l.range = static_cast<float>(gl.range);
    l.position = glm::vec3(world[3]);
    glm::vec3 forward = -glm::vec3(world[2]);
    l.direction = glm::length(forward) > 0 ? glm::normalize(forward) : glm::vec3(NAN);
    // Whether it casts shadows: the node's extras.lightpass.casts_shadows, a boolean, when given.
    if (node.extras.Has("lightpass") && node.extras.Get("lightpass").Has("casts_shadows")) {
      const auto& casts = node.extras.Get("lightpass").Get("casts_shadows");
      if (!casts.IsBool())
        throw Error(file() + ": node '" + name + "': extras.lightpass.casts_shadows must be true or false");
      l.casts_shadows = casts.Get<bool>();
    }
    if (gl.type == "directional") l.type = LightType::Directional;
    else if (gl.type == "point") l.type = LightType::Point;
    else if (gl.type == "spot") {
      l.type = LightType::Spot;
      l.inner_cone = static_cast<float>(gl.spot.innerConeAngle);
      l.outer_cone = static_cast<float>(gl.spot.outerConeAngle);
    } else {
      drop_light(l.name, "its type '" + gl.type + "' is unknown");
      return;
    }
    // One rule for every chapter (light_defect): a light glTF does not allow is left out, by name, here.
    if (const auto why = light_defect(l)) return drop_light(l.name, *why);
    s_.lights.push_back(l);
  }

  void drop_light(const std::string& name, const std::string& why) {
    if (dropped_lights_.insert(name).second) warn("light '" + name + "' is left out: " + why);  // once per light, however many nodes use it
  }

  // The world-space bounds of every instance, exact (each distinct vertex transformed) while
  // that is cheap, else the transformed corners of each mesh's own bounds (a little larger).
  void compute_bounds() {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    std::vector<std::vector<std::uint32_t>> used(s_.meshes.size());
    std::vector<char> seen(s_.vertices.size(), 0);
    std::size_t work = 0;
    for (size_t m = 0; m < s_.meshes.size(); ++m) {
      for (const auto& p : s_.meshes[m].primitives)
        for (std::uint32_t i = p.first_index; i < p.first_index + p.index_count; ++i)
          if (!seen[s_.indices[i]]) {
            seen[s_.indices[i]] = 1;
            used[m].push_back(s_.indices[i]);
          }
      std::sort(used[m].begin(), used[m].end());
    }
    for (const auto& inst : s_.instances) work += used[inst.mesh].size();
    constexpr std::size_t kExactWork = 50'000'000;
    for (const auto& inst : s_.instances) {
      const auto& vs = used[inst.mesh];
      if (work <= kExactWork) {
        for (std::uint32_t v : vs) {
          glm::vec3 w = glm::vec3(inst.model * glm::vec4(s_.vertices[v].position, 1));
          lo = glm::min(lo, w);
          hi = glm::max(hi, w);
        }
        continue;
      }
      glm::vec3 mlo(std::numeric_limits<float>::max()), mhi(-std::numeric_limits<float>::max());
      for (std::uint32_t v : vs) {
        mlo = glm::min(mlo, s_.vertices[v].position);
        mhi = glm::max(mhi, s_.vertices[v].position);
      }
      if (vs.empty()) continue;
      for (int c = 0; c < 8; ++c) {
        glm::vec3 corner((c & 1) ? mhi.x : mlo.x, (c & 2) ? mhi.y : mlo.y, (c & 4) ? mhi.z : mlo.z);
        glm::vec3 w = glm::vec3(inst.model * glm::vec4(corner, 1));
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
      }
    }
    if (!(lo.x <= hi.x)) lo = hi = glm::vec3(0);
    if (!finite(lo) || !finite(hi)) throw Error(file() + ": the scene's bounds are not finite (vertices or transforms too large)");
    s_.bounds_min = lo;
    s_.bounds_max = hi;
  }

  // A view of the whole scene, after the file's cameras: from the front (+Z), a little above
  // and to the right, far enough that the bounding sphere fits the vertical field of view.
  void add_auto_view() {
    for (const auto& c : s_.cameras)
      if (c.name == kAutoView) return;
    const glm::vec3 centre = 0.5f * (s_.bounds_min + s_.bounds_max);
    // The radius in double: a float's squares overflow past 1e19 m and underflow below 1e-19 m.
    float radius = static_cast<float>(0.5 * glm::length(glm::dvec3(s_.bounds_max) - glm::dvec3(s_.bounds_min)));
    if (!(radius > 0)) radius = 1;
    Camera cam;
    cam.name = kAutoView;
    cam.yfov = 0.8f;
    const float distance = radius / std::sin(0.5f * cam.yfov) * 1.05f;
    const bool is_default = s_.cameras.empty();
    glm::vec3 back = glm::normalize(glm::vec3(0.45f, 0.35f, 1.f));  // camera +Z: from the centre towards the eye
    if (is_default) back = side_that_sees_front_faces(back);
    const glm::vec3 up = std::abs(back.y) > 0.99f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
    const glm::vec3 eye = centre + back * distance;
    cam.world = glm::inverse(glm::lookAt(eye, centre, up));
    cam.znear = std::max(distance - radius, distance * 1e-3f) * 0.5f;
    cam.zfar = (distance + radius) * 2.f;
    if (!finite(cam.world) || !(cam.zfar > cam.znear) || !std::isfinite(cam.zfar))
      throw Error(file() + ": the scene is too large for a view in float (radius " + number_text(radius) + " m); scale it down");
    s_.cameras.push_back(cam);
    if (is_default) {
      std::ostringstream n;
      n << s_.path.filename().string() << " has no camera: rendering view '" << kAutoView << "', framing its bounds (centre "
        << centre.x << ", " << centre.y << ", " << centre.z << "; radius " << radius << ")";
      s_.notes.push_back(n.str());
    }
  }

  // Far from the origin a float's step is a visible part of the model (1 m at 1e7 m): the
  // whole scene is moved so that its bounds are centred on the origin, as real viewers do.
  // Each node's transform already holds its offset in float, so a single model is exact; the
  // file's own vertex data cannot be made finer than the file stored it.
  void rebase_far_scene() {
    const glm::dvec3 lo(s_.bounds_min), hi(s_.bounds_max);
    const glm::dvec3 centre = 0.5 * (lo + hi);
    const double radius = 0.5 * glm::length(hi - lo), distance = glm::length(centre);
    if (!(distance > 1e4 && distance > 1e3 * radius)) return;
    const glm::vec3 shift(centre);
    for (auto& i : s_.instances) i.model[3] -= glm::vec4(shift, 0);
    for (auto& l : s_.lights) l.position -= shift;
    for (auto& c : s_.cameras) c.world[3] -= glm::vec4(shift, 0);
    for (auto& e : s_.node_extras) e.world[3] -= glm::vec4(shift, 0);
    s_.bounds_min -= shift;
    s_.bounds_max -= shift;
    std::ostringstream n;
    n << s_.path.filename().string() << " lies " << distance << " m from the origin, where float positions are coarse: "
      << "moved by (" << -shift.x << ", " << -shift.y << ", " << -shift.z << ") to centre it";
    s_.notes.push_back(n.str());
  }

  // The shaders square distances: a scene 1e-19 m across underflows float (its light is 0), one
  // 1e19 m across overflows it. Outside [1e-6, 1e15] m the whole scene is scaled by a power of
  // two (exact) to about 1 m, the lights' intensities by its square and ranges with it, so the
  // image is the one the file describes. Said in a note.
  void rescale_extreme_scene() {
    const double radius = 0.5 * glm::length(glm::dvec3(s_.bounds_max) - glm::dvec3(s_.bounds_min));
    if (!(radius > 0) || (radius >= 1e-6 && radius <= 1e15)) return;
    const int exponent = -static_cast<int>(std::lround(std::log2(radius)));
    const float s = std::ldexp(1.f, exponent);
    const glm::mat4 scale = glm::scale(glm::mat4(1), glm::vec3(s));
    for (auto& i : s_.instances) i.model = scale * i.model;
    for (auto& e : s_.node_extras) e.world = scale * e.world;
    for (auto& c : s_.cameras) {
      c.world[3] = glm::vec4(glm::vec3(c.world[3]) * s, 1);
      c.znear *= s;
      c.zfar *= s;
    }
    for (auto& l : s_.lights) {
      l.position *= s;
      l.range *= s;
      if (l.type != LightType::Directional) l.intensity *= s * s;  // the same irradiance at the scaled distance
    }
    s_.bounds_min *= s;
    s_.bounds_max *= s;
    std::ostringstream n;
    n << s_.path.filename().string() << " is " << 2 * radius << " m across, where float lighting " << (radius < 1 ? "underflows" : "overflows")
      << ": drawn scaled by 2^" << exponent << " (the lights' intensities and ranges with it: the same image)";
    s_.notes.push_back(n.str());
  }

  // A far plane millions of near planes away leaves a 24-bit depth buffer no steps for the
  // scene (past 2^24 znear everything lies at the far plane and the depth test passes nothing):
  // the far plane is brought in to the scene's far side, then the near plane out, each said.
  void usable_depth_ranges() {
    constexpr float kDeepest = 1 << 20;  // zfar / znear
    for (auto& c : s_.cameras) {
      if (c.zfar / c.znear <= kDeepest) continue;
      const float znear = c.znear, zfar = c.zfar;
      float farthest = 0;
      for (int k = 0; k < 8; ++k) {
        const glm::vec3 corner((k & 1) ? s_.bounds_max.x : s_.bounds_min.x, (k & 2) ? s_.bounds_max.y : s_.bounds_min.y,
                               (k & 4) ? s_.bounds_max.z : s_.bounds_min.z);
        farthest = std::max(farthest, glm::length(corner - c.position()));
      }
      c.zfar = std::min(c.zfar, farthest * 1.01f);
      if (!(c.zfar > c.znear)) c.zfar = zfar;
      if (!(c.zfar / c.znear <= kDeepest)) c.znear = c.zfar / kDeepest;
      warn("camera '" + c.name + "': znear " + number_text(znear) + " beside zfar " + number_text(zfar) +
           " leaves the depth buffer no precision (everything would lie at the far plane); using znear " + number_text(c.znear) +
           ", zfar " + number_text(c.zfar));
    }
  }

  // A range of a millionth of the scene's size lights nothing that can be seen: left out, said.
  void drop_lights_of_no_range() {
    const float size = glm::length(s_.bounds_max - s_.bounds_min);
    std::erase_if(s_.lights, [&](const Light& l) {
      if (!(l.range > 0 && l.range < 1e-6f * size)) return false;
      drop_light(l.name, "its range " + number_text(l.range) + " m is a millionth of the scene's size (" + number_text(size) +
                             " m across) or less: it lights nothing");
      return true;
    });
  }

  // A small file can name 100 000 lights that each reach every pixel (a DAG of light nodes):
  // the work a frame does for them is bounded here, in whole scenes lit, and said above 256.
  void bound_light_work() {
    const float size = glm::length(s_.bounds_max - s_.bounds_min);
    double reach = 0;
    for (const auto& l : s_.lights)
      reach += l.type == LightType::Directional || !(l.range > 0) || !(size > 0) ? 1.0 : std::min(1.0, std::pow(2.0 * l.range / size, 2.0));
    std::ostringstream text;
    text << "its " << s_.lights.size() << " lights reach " << std::setprecision(3) << reach
         << " times the whole scene (each light counts the share of the scene its range covers; without a range, all of it)";
    if (reach > limits.max_light_reach)
      throw Error(file() + ": " + text.str() + ", more work a frame than the loader accepts (" + number_text(limits.max_light_reach) +
                  "); give the lights a range");
    if (reach > 256) warn(text.str() + ": every pixel is shaded that many times, expect slow frames");
  }

  // Where the automatic view looks from: `preferred` (from the front, above, right) unless from
  // there every face that is drawn one-sided (glTF's default) points away, and the image would
  // be the background; then the octant that sees the most front-facing area, said in a note.
  glm::vec3 side_that_sees_front_faces(glm::vec3 preferred) {
    std::size_t work = 0;
    for (const auto& inst : s_.instances)
      for (const auto& p : s_.meshes[std::size_t(inst.mesh)].primitives) work += p.index_count / 3;
    if (work > 20'000'000) return preferred;  // too many to weigh: keep the usual side
    std::array<glm::vec3, 8> sides;
    for (int k = 0; k < 8; ++k) sides[std::size_t(k)] = preferred * glm::vec3((k & 1) ? -1 : 1, (k & 2) ? -1 : 1, (k & 4) ? -1 : 1);
    std::array<double, 8> seen{};
    for (const auto& inst : s_.instances)
      for (const auto& p : s_.meshes[std::size_t(inst.mesh)].primitives) {
        const bool both = s_.materials[std::size_t(p.material)].double_sided;
        for (std::uint32_t t = p.first_index; t + 2 < p.first_index + p.index_count; t += 3) {
          auto at = [&](std::uint32_t i) { return glm::dvec3(inst.model * glm::vec4(s_.vertices[s_.indices[i]].position, 1)); };
          const glm::dvec3 a = at(t), area = glm::cross(at(t + 1) - a, at(t + 2) - a);
          for (std::size_t k = 0; k < 8; ++k) {
            const double facing = glm::dot(area, glm::dvec3(sides[k]));
            seen[k] += both ? std::abs(facing) : std::max(0.0, facing);
          }
        }
      }
    const std::size_t best = std::size_t(std::max_element(seen.begin(), seen.end()) - seen.begin());
    if (seen[0] > 1e-3 * seen[best] || !(seen[best] > 0)) return preferred;
    std::ostringstream n;
    n << "every face of " << s_.path.filename().string() << " faces away from the automatic view's usual side (glTF draws "
      << "one side only): looking from the other side, towards (" << -sides[best].x << ", " << -sides[best].y << ", "
      << -sides[best].z << ")";
    s_.notes.push_back(n.str());
    return sides[best];
  }

  // A scene without lights would be black: a key light from the default view's left and
  // above, so that shadows fall sideways onto what is visible (from behind the camera they
  // hid behind the model), a dim fill from the right, and a little ambient; together at most
  // 1 on a surface facing up or facing the view, so a grey floor does not clip.
  // A scene whose every light was left out gets the same rig, warned; one whose lights give
  // no light is only warned about.
  void add_default_lights() {
    bool emissive = false;
    for (const auto& m : s_.materials) emissive |= glm::any(glm::greaterThan(m.emissive, glm::vec3(0)));
    const bool ambient = glm::any(glm::greaterThan(s_.ambient, glm::vec3(0)));
    if (lights_declared_ == 0 || s_.lights.empty()) {
      const Camera& view = s_.cameras.front();
      // "Above" is the side the view sees from: a view from below (the automatic view turned
      // to see faces that point down) gets its key from below too, or it lights their backs.
      const glm::vec3 right(view.world[0]), back(view.world[2]);
      const glm::vec3 up = glm::vec3(view.world[1]) * (back.y < 0.f ? -1.f : 1.f);
      auto light = [&](const char* name, glm::vec3 towards, float lux) {
        Light l{.name = name, .type = LightType::Directional, .intensity = lux};
        l.direction = -glm::normalize(towards);
        s_.lights.push_back(l);
      };
      light("default_key", -1.0f * right + 1.1f * up + 0.7f * back, 0.8f);
      light("default_fill", 0.8f * right + 0.2f * up + 0.6f * back, 0.25f);
      if (!ambient) s_.ambient = glm::vec3(0.05f);
      const std::string rig = "a default rig (a directional key from the left of and above view '" + view.name +
                              "', a fill from the right" + (ambient ? "" : ", ambient 0.05") + ")";
      if (lights_declared_ == 0) s_.notes.push_back(s_.path.filename().string() + " has no lights: using " + rig);
      else warn("none of the scene's " + std::to_string(lights_declared_) + " lights can be used (each is named above): using " + rig);
      return;
    }
    bool lit = false;
    for (const auto& l : s_.lights) lit |= l.intensity > 0 && glm::any(glm::greaterThan(l.color, glm::vec3(0)));
    if (!lit && !emissive && !ambient)
      warn("the image will be black: of the scene's " + std::to_string(lights_declared_) +
           " lights none gives light (left out, or zero intensity or colour), and it has no ambient or emissive light");
  }

  void warn(const std::string& w) { s_.warnings.push_back(w); }

  const tinygltf::Model& m_;
  Scene& s_;
  const ImageContext& images_;
  const FileContext& files_;
  const SceneLimits limits;
  const IndexFixups& fixups_;
  int default_material_ = 0;
  std::vector<int> mesh_of_gltf_;
  std::vector<UvTransform> uv_transform_;  // per Scene::materials index
  std::vector<std::optional<glm::mat4>> local_;  // per node, once: a shared child is met many times
  std::vector<std::optional<std::string>> extras_json_;  // per node, once
  std::set<std::string> dropped_lights_;
  std::size_t copied_bytes_ = 0;
  std::map<std::pair<int, bool>, int> texture_of_key_;  // (glTF texture, sRGB) and (-1 - image, sRGB) -> Scene texture
  std::map<std::string, int> unsupported_;
  std::size_t visits_ = 0, skipped_primitives_ = 0, lights_declared_ = 0, zero_area_triangles_ = 0;
};

}  // namespace

std::optional<std::string> light_defect(const Light& l) {
  if (!finite(l.color) || glm::any(glm::lessThan(l.color, glm::vec3(0)))) return "its colour is negative or not finite";
  if (!finite(l.intensity) || l.intensity < 0) return "its intensity " + number_text(l.intensity) + " is negative or not finite";
  if (!finite(l.range) || l.range < 0) return "its range " + number_text(l.range) + " is negative or not finite";
  if (l.type != LightType::Directional && !finite(l.position)) return "its position is not finite";
  if (l.type != LightType::Point && !(finite(l.direction) && glm::length(l.direction) > 0))
    return "it has no direction (zero, or not finite: a node of zero scale)";
  // glTF allows outer <= pi/2; a wider spot still has a meaning (chapter 03 draws it with a
  // sphere, and says so), angles that make no cone do not.
  if (l.type == LightType::Spot &&
      !(l.inner_cone >= 0 && l.inner_cone <= l.outer_cone && l.outer_cone > 0 && l.outer_cone < std::numbers::pi_v<float>))
    return "its cone angles (inner " + number_text(l.inner_cone) + ", outer " + number_text(l.outer_cone) +
           ") are not 0 <= inner <= outer < pi";
  return std::nullopt;
}

const Camera& Scene::camera(const std::string& name) const {
  for (const auto& c : cameras)
    if (c.name == name) return c;
  std::string names;
  for (const auto& c : cameras) names += " " + c.name;
  throw Error(path.string() + " has no camera named '" + name + "'; views:" + (names.empty() ? " (none)" : names));
}

void generate_normals(std::vector<Vertex>& v, const std::vector<std::uint32_t>& idx, std::uint32_t first, std::uint32_t count) {
  for (std::uint32_t i = first; i < first + count; ++i) v[idx[i]].normal = glm::vec3(0);
  for (std::uint32_t t = first; t + 2 < first + count; t += 3) {
    Vertex &a = v[idx[t]], &b = v[idx[t + 1]], &c = v[idx[t + 2]];
    glm::vec3 n = glm::cross(b.position - a.position, c.position - a.position);  // length = 2 x area
    a.normal += n; b.normal += n; c.normal += n;
  }
  for (std::uint32_t i = first; i < first + count; ++i) {
    glm::vec3& n = v[idx[i]].normal;
    float len = glm::length(n);
    n = len > 0 ? n / len : glm::vec3(0, 1, 0);
  }
}

// [generated-tangents]
// Tangents where the file has none. glTF asks for MikkTSpace, which Debian does not package;
// this is the classic per-triangle construction it refines: each triangle's tangent and
// bitangent from its UV derivatives, summed at the vertices it shares, made perpendicular to
// the normal (Gram-Schmidt), the handedness from the summed bitangent. It equals MikkTSpace
// on flat, evenly mapped surfaces and differs a little across curved, unevenly mapped ones.
void generate_tangents(std::vector<Vertex>& v, const std::vector<std::uint32_t>& idx, std::uint32_t first, std::uint32_t count, bool has_uv) {
  std::vector<glm::vec3> bitangent(v.size(), glm::vec3(0));
  for (std::uint32_t i = first; i < first + count; ++i) v[idx[i]].tangent = glm::vec4(0);
  if (has_uv) {
    for (std::uint32_t t = first; t + 2 < first + count; t += 3) {
      std::uint32_t ia = idx[t], ib = idx[t + 1], ic = idx[t + 2];
      glm::vec3 e1 = v[ib].position - v[ia].position, e2 = v[ic].position - v[ia].position;
      glm::vec2 d1 = v[ib].uv - v[ia].uv, d2 = v[ic].uv - v[ia].uv;
      float det = d1.x * d2.y - d2.x * d1.y;
      if (std::abs(det) < 1e-12f) continue;  // degenerate UVs: this triangle gives no direction
      glm::vec3 tangent = (e1 * d2.y - e2 * d1.y) / det;
      glm::vec3 bitan = (e2 * d1.x - e1 * d2.x) / det;
      for (std::uint32_t k : {ia, ib, ic}) {
        v[k].tangent += glm::vec4(tangent, 0);
        bitangent[k] += bitan;
      }
    }
  }
  for (std::uint32_t i = first; i < first + count; ++i) {
    Vertex& x = v[idx[i]];
    glm::vec3 t = glm::vec3(x.tangent) - x.normal * glm::dot(x.normal, glm::vec3(x.tangent));  // Gram-Schmidt
    if (!(glm::length(t) >= 1e-6f)) {
      // No usable UVs: any unit vector perpendicular to the normal will do.
      glm::vec3 axis = std::abs(x.normal.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
      t = glm::cross(axis, x.normal);
      if (!(glm::length(t) > 0)) t = axis;  // a zero normal: any axis
    }
    t = glm::normalize(t);
    // glTF: bitangent = cross(N, T) * w points up the image, i.e. towards -v (v runs down).
    float w = glm::dot(glm::cross(x.normal, t), bitangent[idx[i]]) > 0 ? -1.f : 1.f;
    x.tangent = glm::vec4(t, w);
  }
}
// [/generated-tangents]

Scene load_scene_from_memory(const std::vector<unsigned char>& bytes, const std::filesystem::path& path, const SceneLimits& limits) {
  if (bytes.empty()) throw Error("cannot load scene '" + path.string() + "': the file is empty");
  if (bytes.size() > limits.max_file_bytes) throw Error("cannot load scene '" + path.string() + "': the file is too large");
  // A .glb starts with the magic "glTF", whatever the file is called.
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  const unsigned char* json = bytes.data();
  std::size_t json_size = bytes.size();
  if (binary && bytes.size() >= 20) {
    std::uint32_t chunk0 = 0;
    std::memcpy(&chunk0, bytes.data() + 12, 4);
    json = bytes.data() + 20;
    json_size = std::min<std::size_t>(chunk0, bytes.size() - 20);
  }
  if (json_too_deep(json, json_size))
    throw Error("cannot load scene '" + path.string() + "': its JSON nests deeper than " + std::to_string(kMaxJsonDepth) + " levels");
  std::vector<unsigned char> rewritten;
  const IndexFixups fixups = check_before_tinygltf(json, json_size, path, binary && bytes.size() >= 20 ? &bytes : nullptr, rewritten);
  const std::vector<unsigned char>& input = rewritten.empty() ? bytes : rewritten;

  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string base = path.parent_path().string();
  if (base.empty()) base = ".";
  FileContext files{.max_bytes = limits.max_file_bytes, .base = base};
  ImageContext images{.model = &model, .limits = limits};
  loader.SetFsCallbacks({.FileExists = fs_exists, .ExpandFilePath = fs_expand, .ReadWholeFile = fs_read,
                         .WriteWholeFile = fs_write, .user_data = &files});
  loader.SetImageLoader(load_image, &images);
  std::string err, warn;
  bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, input.data(), static_cast<unsigned>(input.size()), base)
                   : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(input.data()),
                                                static_cast<unsigned>(input.size()), base);
  if (!ok) {
    // tinygltf quotes the file where its JSON fails: a .glb's bytes reach the terminal as they
    // are. Control and non-ASCII bytes are shown as \xNN, and the message is cut short.
    std::string said;
    for (unsigned char c : err) {
      if (said.size() > 400) {
        said += "...";
        break;
      }
      if (c == '\n' || (c >= 0x20 && c < 0x7F)) said += char(c);
      else {
        char hex[8];
        std::snprintf(hex, sizeof hex, "\\x%02X", c);
        said += hex;
      }
    }
    while (!said.empty() && said.back() == '\n') said.pop_back();
    if (said.find("File not found") != std::string::npos && !files.problems.empty()) said = files.problems.front();
    throw Error("cannot load scene '" + path.string() + "': " + (said.empty() ? "not valid glTF" : said));
  }
  for (const auto& e : model.extensionsRequired)
    if (!supported_extensions().count(e))
      throw Error("cannot load scene '" + path.string() + "': it requires the extension " + e + ", which lightpass does not support");
  Scene scene;
  scene.path = path;
  Loader(model, scene, images, files, limits, fixups).load();
  return scene;
}

Scene load_scene(const std::filesystem::path& path, const SceneLimits& limits) {
  std::vector<unsigned char> bytes;
  std::string why = read_problem(path, &bytes, limits.max_file_bytes);
  if (why == "no such file") throw Error("cannot open scene '" + path.string() + "': no such file");
  if (!why.empty()) throw Error("cannot read scene '" + path.string() + "': " + why);
  return load_scene_from_memory(bytes, path, limits);
}

}  // namespace lp
