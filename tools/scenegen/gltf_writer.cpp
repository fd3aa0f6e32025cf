#include "gltf_writer.h"

#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace scenegen {

namespace {

constexpr int kFloat = 5126, kUShort = 5123, kUInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

void write_file(const std::filesystem::path& path, const void* data, size_t size) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f) throw std::runtime_error("cannot create " + path.string());
  f.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!f) throw std::runtime_error("cannot write " + path.string());
}

bool is_scalar(const json& j) { return !j.is_object() && !j.is_array(); }

void emit(const json& j, std::string& out, int depth) {
  const std::string pad(static_cast<size_t>(depth + 1) * 2, ' ');
  if (j.is_object()) {
    if (j.empty()) {
      out += "{}";
      return;
    }
    out += "{\n";
    size_t i = 0;
    for (auto it = j.begin(); it != j.end(); ++it, ++i) {
      out += pad + json(it.key()).dump() + ": ";
      emit(it.value(), out, depth + 1);
      out += (i + 1 < j.size()) ? ",\n" : "\n";
    }
    out += std::string(static_cast<size_t>(depth) * 2, ' ') + "}";
  } else if (j.is_array()) {
    if (j.empty()) {
      out += "[]";
      return;
    }
    bool flat = true;
    for (const auto& e : j) flat = flat && is_scalar(e);
    if (flat && j.size() <= 16) {
      out += "[";
      for (size_t i = 0; i < j.size(); ++i) out += (i ? ", " : "") + j[i].dump();
      out += "]";
      return;
    }
    out += "[\n";
    for (size_t i = 0; i < j.size(); ++i) {
      if (flat) {
        if (i % 16 == 0) out += pad;
        out += j[i].dump();
        out += (i + 1 < j.size()) ? ((i % 16 == 15) ? ",\n" : ", ") : "\n";
      } else {
        out += pad;
        emit(j[i], out, depth + 1);
        out += (i + 1 < j.size()) ? ",\n" : "\n";
      }
    }
    out += std::string(static_cast<size_t>(depth) * 2, ' ') + "]";
  } else {
    out += j.dump();
  }
}

}  // namespace

double fnum(float v) {
  if (v == 0.0f) return 0.0;  // no "-0.0"
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof buf, v);  // shortest round-trip float text
  double d = 0.0;
  std::from_chars(buf, res.ptr, d);
  return d;  // nlohmann prints this double with the same (shortest) digits
}

json jvec(const glm::vec2& v) { return json::array({fnum(v.x), fnum(v.y)}); }
json jvec(const glm::vec3& v) { return json::array({fnum(v.x), fnum(v.y), fnum(v.z)}); }
json jvec(const glm::vec4& v) { return json::array({fnum(v.x), fnum(v.y), fnum(v.z), fnum(v.w)}); }

json jquat(const glm::quat& q_in) {
  glm::quat q = glm::normalize(q_in);
  if (q.w < 0.0f) q = -q;
  auto clean = [](float x) { return std::fabs(x) < 1e-7f ? 0.0f : x; };
  return json::array({fnum(clean(q.x)), fnum(clean(q.y)), fnum(clean(q.z)), fnum(clean(q.w))});
}

glm::quat look_rotation(const glm::vec3& forward, const glm::vec3& up) {
  const glm::vec3 f = glm::normalize(forward);
  glm::vec3 r = glm::cross(f, up);
  if (glm::length(r) < 1e-4f) r = glm::cross(f, std::fabs(f.z) < 0.9f ? glm::vec3(0, 0, -1) : glm::vec3(1, 0, 0));
  r = glm::normalize(r);
  const glm::vec3 u = glm::cross(r, f);
  return glm::normalize(glm::quat_cast(glm::mat3(r, u, -f)));
}

glm::quat frame_rotation(const glm::mat3& frame) { return glm::normalize(glm::quat_cast(frame)); }

std::string format_json(const json& j) {
  std::string out;
  emit(j, out, 0);
  out += "\n";
  return out;
}

GltfBuilder::GltfBuilder(std::string name) : name_(std::move(name)) {}

int GltfBuilder::add_view(const void* data, size_t bytes, int target) {
  while (bin_.size() % 4) bin_.push_back(0);
  const size_t offset = bin_.size();
  bin_.resize(offset + bytes);
  std::memcpy(bin_.data() + offset, data, bytes);
  json v = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}};
  if (target) v["target"] = target;
  buffer_views_.push_back(v);
  return static_cast<int>(buffer_views_.size()) - 1;
}

int GltfBuilder::add_accessor(int view, int component_type, size_t count, const char* type, const json& min,
                              const json& max) {
  json a = {{"bufferView", view}, {"componentType", component_type}, {"count", count}, {"type", type}};
  if (!min.is_null()) a["min"] = min;
  if (!max.is_null()) a["max"] = max;
  accessors_.push_back(a);
  return static_cast<int>(accessors_.size()) - 1;
}

int GltfBuilder::add_material(const Material& m) {
  json pbr = {{"baseColorFactor", jvec(m.base_color)}, {"metallicFactor", fnum(m.metallic)},
              {"roughnessFactor", fnum(m.roughness)}};
  if (m.base_color_texture >= 0) pbr["baseColorTexture"] = {{"index", m.base_color_texture}};
  json mat = {{"name", m.name},
              {"pbrMetallicRoughness", pbr},
              {"emissiveFactor", jvec(m.emissive)},
              {"extensions",
               {{"KHR_materials_specular",
                 {{"specularFactor", fnum(m.specular)}, {"specularColorFactor", jvec(m.specular_color)}}}}}};
  if (m.normal_texture >= 0) mat["normalTexture"] = {{"index", m.normal_texture}};
  if (!m.alpha_mode.empty()) mat["alphaMode"] = m.alpha_mode;
  materials_.push_back(mat);
  return static_cast<int>(materials_.size()) - 1;
}

int GltfBuilder::add_texture(const std::string& uri) {
  images_.push_back({{"uri", uri}, {"name", std::filesystem::path(uri).stem().string()}});
  textures_.push_back({{"source", images_.size() - 1}, {"sampler", 0}});
  return static_cast<int>(textures_.size()) - 1;
}

int GltfBuilder::add_mesh(const std::string& name, const Mesh& mesh, int material, IndexType index_type) {
  const size_t n = mesh.vertex_count();
  if (n == 0) throw std::runtime_error("mesh " + name + " is empty");
  json attributes = json::object();
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const auto& p : mesh.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  attributes["POSITION"] = add_accessor(add_view(mesh.positions.data(), n * sizeof(glm::vec3), kArrayBuffer), kFloat,
                                        n, "VEC3", jvec(lo), jvec(hi));
  auto check = [&](size_t size, const char* what) {
    if (size != 0 && size != n) throw std::runtime_error("mesh " + name + ": " + what + " count differs");
    return size != 0;
  };
  if (check(mesh.normals.size(), "normal"))
    attributes["NORMAL"] = add_accessor(add_view(mesh.normals.data(), n * sizeof(glm::vec3), kArrayBuffer), kFloat, n, "VEC3");
  if (check(mesh.uvs.size(), "uv"))
    attributes["TEXCOORD_0"] = add_accessor(add_view(mesh.uvs.data(), n * sizeof(glm::vec2), kArrayBuffer), kFloat, n, "VEC2");
  if (check(mesh.tangents.size(), "tangent"))
    attributes["TANGENT"] = add_accessor(add_view(mesh.tangents.data(), n * sizeof(glm::vec4), kArrayBuffer), kFloat, n, "VEC4");
  json prim = {{"attributes", attributes}, {"mode", 4}};
  if (!mesh.indices.empty()) {
    uint32_t max_index = 0;
    for (uint32_t i : mesh.indices) max_index = std::max(max_index, i);
    const bool u16 = index_type == IndexType::U16 || (index_type == IndexType::Auto && max_index < 65535u);
    int view;
    if (u16) {
      std::vector<uint16_t> idx(mesh.indices.begin(), mesh.indices.end());
      view = add_view(idx.data(), idx.size() * sizeof(uint16_t), kElementArrayBuffer);
    } else {
      view = add_view(mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t), kElementArrayBuffer);
    }
    prim["indices"] = add_accessor(view, u16 ? kUShort : kUInt, mesh.indices.size(), "SCALAR");
  }
  if (material >= 0) prim["material"] = material;
  meshes_.push_back({{"name", name}, {"primitives", json::array({prim})}});
  return static_cast<int>(meshes_.size()) - 1;
}

int GltfBuilder::add_node(json node) {
  nodes_.push_back(std::move(node));
  return static_cast<int>(nodes_.size()) - 1;
}

int GltfBuilder::add_mesh_node(const std::string& name, int mesh, const glm::vec3& translation,
                               const std::optional<glm::quat>& rotation, const json& lightpass_extras) {
  json node = {{"name", name}, {"mesh", mesh}, {"translation", jvec(translation)}};
  if (rotation) node["rotation"] = jquat(*rotation);
  if (!lightpass_extras.is_null()) node["extras"] = {{"lightpass", lightpass_extras}};
  return add_node(node);
}

int GltfBuilder::add_sphere_node(const std::string& name, int mesh, const glm::vec3& centre, float radius) {
  return add_mesh_node(name, mesh, centre, std::nullopt, {{"shape", "sphere"}, {"radius", fnum(radius)}});
}

int GltfBuilder::add_rect_node(const std::string& name, int mesh, const glm::vec3& centre, const glm::mat3& frame,
                               float sx, float sz) {
  const glm::quat q = frame_rotation(frame);
  const bool identity = std::fabs(q.w) > 1.0f - 1e-7f;
  return add_mesh_node(name, mesh, centre, identity ? std::nullopt : std::optional<glm::quat>(q),
                       {{"shape", "rect"}, {"size", jvec(glm::vec2(sx, sz))}});
}

int GltfBuilder::add_camera(const std::string& name, const glm::vec3& eye, const glm::vec3& target, float yfov,
                            float znear, float zfar, const glm::vec3& up) {
  cameras_.push_back({{"name", name},
                      {"type", "perspective"},
                      {"perspective",
                       {{"aspectRatio", fnum(16.0f / 9.0f)}, {"yfov", fnum(yfov)}, {"znear", fnum(znear)}, {"zfar", fnum(zfar)}}}});
  return add_node({{"name", name},
                   {"camera", cameras_.size() - 1},
                   {"translation", jvec(eye)},
                   {"rotation", jquat(look_rotation(target - eye, up))}});
}

int GltfBuilder::add_light(json light, const glm::vec3& position, const std::optional<glm::quat>& rotation) {
  lights_.push_back(light);
  json node = {{"name", light["name"]},
               {"extensions", {{"KHR_lights_punctual", {{"light", lights_.size() - 1}}}}}};
  node["translation"] = jvec(position);
  if (rotation) node["rotation"] = jquat(*rotation);
  return add_node(node);
}

int GltfBuilder::add_point_light(const std::string& name, const glm::vec3& position, const glm::vec3& color,
                                 float candela, float range) {
  json l = {{"name", name}, {"type", "point"}, {"color", jvec(color)}, {"intensity", fnum(candela)}};
  if (range > 0.0f) l["range"] = fnum(range);
  return add_light(l, position, std::nullopt);
}

int GltfBuilder::add_spot_light(const std::string& name, const glm::vec3& position, const glm::vec3& direction,
                                const glm::vec3& color, float candela, float inner, float outer, float range) {
  json l = {{"name", name},
            {"type", "spot"},
            {"color", jvec(color)},
            {"intensity", fnum(candela)},
            {"spot", {{"innerConeAngle", fnum(inner)}, {"outerConeAngle", fnum(outer)}}}};
  if (range > 0.0f) l["range"] = fnum(range);
  return add_light(l, position, look_rotation(direction));
}

int GltfBuilder::add_directional_light(const std::string& name, const glm::vec3& direction, const glm::vec3& color,
                                       float lux) {
  json l = {{"name", name}, {"type", "directional"}, {"color", jvec(color)}, {"intensity", fnum(lux)}};
  // The position of a directional light does not matter; put the node "up-sun" for viewers.
  return add_light(l, -glm::normalize(direction) * 20.0f, look_rotation(direction));
}

json GltfBuilder::document(const std::string& buffer_uri) const {
  json doc;
  doc["asset"] = {{"version", "2.0"}, {"generator", "lightpass tools/scenegen"}};
  json used = json::array();
  if (!lights_.empty()) {
    used.push_back("KHR_lights_punctual");
    doc["extensions"] = {{"KHR_lights_punctual", {{"lights", lights_}}}};
  }
  if (!materials_.empty()) used.push_back("KHR_materials_specular");
  if (!used.empty()) doc["extensionsUsed"] = used;
  json scene_nodes = json::array();
  for (size_t i = 0; i < nodes_.size(); ++i) scene_nodes.push_back(i);
  doc["scene"] = 0;
  json lightpass = scene_extras_;
  lightpass["ambient"] = jvec(ambient_);
  doc["scenes"] = json::array({{{"name", name_}, {"nodes", scene_nodes}, {"extras", {{"lightpass", lightpass}}}}});
  auto put = [&](const char* key, const json& arr) {
    if (!arr.empty()) doc[key] = arr;  // glTF forbids empty top-level arrays
  };
  put("nodes", nodes_);
  put("meshes", meshes_);
  put("materials", materials_);
  put("textures", textures_);
  put("images", images_);
  if (!textures_.empty())
    doc["samplers"] = json::array({{{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 10497}, {"wrapT", 10497}}});
  put("cameras", cameras_);
  put("accessors", accessors_);
  put("bufferViews", buffer_views_);
  if (!bin_.empty())
    doc["buffers"] = json::array({{{"byteLength", bin_.size()}, {"uri", buffer_uri.empty() ? name_ + ".bin" : buffer_uri}}});
  return doc;
}

void GltfBuilder::write(const std::filesystem::path& dir) const {
  std::filesystem::create_directories(dir);
  const std::string text = format_json(document());
  write_file(dir / (name_ + ".gltf"), text.data(), text.size());
  if (!bin_.empty()) write_file(dir / (name_ + ".bin"), bin_.data(), bin_.size());
}

}  // namespace scenegen
