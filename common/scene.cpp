#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE_WRITE
#include <tiny_gltf.h>

#include "common/scene.h"

#include <algorithm>
#include <cstring>
#include <functional>
#include <iostream>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include "common/error.h"

namespace lp {
namespace {

// Reads accessor elements as floats (or as indices), checking every byte it touches, so a
// malformed file becomes an error message rather than an out-of-bounds read.
class AccessorReader {
 public:
  AccessorReader(const tinygltf::Model& m, int index, const std::string& where) : where_(where) {
    if (index < 0 || index >= static_cast<int>(m.accessors.size()))
      fail("accessor " + std::to_string(index) + " does not exist");
    acc_ = &m.accessors[index];
    if (acc_->sparse.isSparse) fail("sparse accessors are not supported");
    if (acc_->bufferView < 0 || acc_->bufferView >= static_cast<int>(m.bufferViews.size()))
      fail("accessor " + std::to_string(index) + " has no buffer view");
    const auto& view = m.bufferViews[acc_->bufferView];
    if (view.buffer < 0 || view.buffer >= static_cast<int>(m.buffers.size())) fail("buffer view has no buffer");
    const auto& buffer = m.buffers[view.buffer];
    components_ = tinygltf::GetNumComponentsInType(acc_->type);
    component_bytes_ = tinygltf::GetComponentSizeInBytes(acc_->componentType);
    if (components_ <= 0 || component_bytes_ <= 0) fail("accessor has an unknown type");
    int elem = components_ * component_bytes_;
    stride_ = view.byteStride ? view.byteStride : elem;
    size_t start = view.byteOffset + acc_->byteOffset;
    size_t need = acc_->count ? start + stride_ * (acc_->count - 1) + elem : start;
    if (view.byteOffset + view.byteLength > buffer.data.size() || need > view.byteOffset + view.byteLength)
      fail("accessor " + std::to_string(index) + " reads past the end of its buffer ('" + buffer.uri + "')");
    data_ = buffer.data.data() + start;
  }
  size_t count() const { return acc_->count; }
  int components() const { return components_; }

  float component(size_t i, int c) const {
    const unsigned char* p = data_ + i * stride_ + c * component_bytes_;
    switch (acc_->componentType) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); return f; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return acc_->normalized ? *p / 255.f : *p;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t v; std::memcpy(&v, p, 2); return acc_->normalized ? v / 65535.f : v; }
      case TINYGLTF_COMPONENT_TYPE_BYTE: { auto v = static_cast<std::int8_t>(*p); return acc_->normalized ? std::max(v / 127.f, -1.f) : v; }
      case TINYGLTF_COMPONENT_TYPE_SHORT: {
        std::int16_t v; std::memcpy(&v, p, 2); return acc_->normalized ? std::max(v / 32767.f, -1.f) : v; }
      default: fail("unsupported component type for a vertex attribute");
    }
  }
  std::uint32_t index(size_t i) const {
    const unsigned char* p = data_ + i * stride_;
    switch (acc_->componentType) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return *p;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { std::uint16_t v; std::memcpy(&v, p, 2); return v; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { std::uint32_t v; std::memcpy(&v, p, 4); return v; }
      default: fail("indices must be unsigned byte, short or int");
    }
  }
  template <int N>
  glm::vec<N, float> vec(size_t i) const {
    glm::vec<N, float> v(0);
    for (int c = 0; c < std::min(N, components_); ++c) v[c] = component(i, c);
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw Error(where_ + ": " + what); }
  const tinygltf::Accessor* acc_ = nullptr;
  const unsigned char* data_ = nullptr;
  int components_ = 0, component_bytes_ = 0;
  size_t stride_ = 0;
  std::string where_;
};

glm::vec3 vec3_or(const std::vector<double>& v, glm::vec3 fallback) {
  return v.size() >= 3 ? glm::vec3(v[0], v[1], v[2]) : fallback;
}

glm::mat4 local_matrix(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) {
    glm::mat4 m;
    for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = static_cast<float>(n.matrix[i]);
    return m;
  }
  glm::mat4 t = glm::translate(glm::mat4(1), vec3_or(n.translation, glm::vec3(0)));
  glm::quat q(1, 0, 0, 0);
  if (n.rotation.size() == 4) q = glm::quat(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]), float(n.rotation[2]));
  glm::mat4 s = glm::scale(glm::mat4(1), vec3_or(n.scale, glm::vec3(1)));
  return t * glm::mat4_cast(q) * s;
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

class Loader {
 public:
  Loader(const tinygltf::Model& m, Scene& s) : m_(m), s_(s) {}

  void load() {
    s_.materials.reserve(m_.materials.size() + 1);
    for (size_t i = 0; i < m_.materials.size(); ++i) s_.materials.push_back(material(m_.materials[i]));
    default_material_ = static_cast<int>(s_.materials.size());
    s_.materials.push_back(Material{.name = "default", .base_color = glm::vec4(0.8f, 0.8f, 0.8f, 1), .specular_color = glm::vec3(0.04f)});
    mesh_of_gltf_.assign(m_.meshes.size(), -1);

    int scene_index = m_.defaultScene >= 0 ? m_.defaultScene : 0;
    if (m_.scenes.empty()) throw Error(s_.path.string() + ": the file has no scene");
    if (scene_index >= static_cast<int>(m_.scenes.size())) throw Error(s_.path.string() + ": default scene does not exist");
    const auto& scene = m_.scenes[scene_index];
    if (scene.extras.Has("lightpass")) {
      const auto& lp = scene.extras.Get("lightpass");
      if (lp.Has("ambient")) s_.ambient = number3(lp.Get("ambient"), glm::vec3(0));
    }
    for (int root : scene.nodes) visit(root, glm::mat4(1), 0);
    if (s_.instances.empty()) throw Error(s_.path.string() + ": the scene has no meshes to draw");
    compute_bounds();
  }

 private:
  static glm::vec3 number3(const tinygltf::Value& v, glm::vec3 fallback) {
    if (!v.IsArray() || v.ArrayLen() < 3) return fallback;
    glm::vec3 r;
    for (int i = 0; i < 3; ++i) r[i] = static_cast<float>(v.Get(i).GetNumberAsDouble());
    return r;
  }

  int texture(int gltf_index, bool srgb, const std::string& material_name) {
    if (gltf_index < 0) return -1;
    for (size_t i = 0; i < texture_keys_.size(); ++i)
      if (texture_keys_[i] == std::make_pair(gltf_index, srgb)) return static_cast<int>(i);
    Texture t;
    t.srgb = srgb;
    const tinygltf::Image* img = nullptr;
    if (gltf_index < static_cast<int>(m_.textures.size())) {
      int source = m_.textures[gltf_index].source;
      if (source >= 0 && source < static_cast<int>(m_.images.size())) img = &m_.images[source];
    }
    t.name = img ? (img->uri.empty() ? img->name : img->uri) : "texture " + std::to_string(gltf_index);
    if (img && img->width > 0 && img->height > 0 && !img->image.empty() && img->bits == 8) {
      t.image.width = img->width;
      t.image.height = img->height;
      t.image.pixels.resize(size_t(img->width) * img->height * 4);
      for (size_t p = 0; p < size_t(img->width) * img->height; ++p)
        for (int c = 0; c < 4; ++c)
          t.image.pixels[p * 4 + c] = c < img->component ? img->image[p * img->component + c]
                                                        : (c == 3 ? 255 : img->image[p * img->component]);
    } else {
      // Magenta checker for colours (impossible to miss), flat normal for normal maps.
      t.image = srgb ? fallback_checker({255, 0, 255, 255}, {32, 32, 32, 255})
                     : fallback_checker({128, 128, 255, 255}, {128, 128, 255, 255});
      t.fallback = true;
      warn("material '" + material_name + "': texture '" + t.name + "' could not be loaded (" +
           (s_.path.parent_path() / t.name).string() + "): using a fallback " + (srgb ? "checker" : "flat normal map"));
    }
    texture_keys_.push_back({gltf_index, srgb});
    s_.textures.push_back(std::move(t));
    return static_cast<int>(s_.textures.size() - 1);
  }

  Material material(const tinygltf::Material& gm) {
    Material mat;
    mat.name = gm.name;
    const auto& pbr = gm.pbrMetallicRoughness;
    if (pbr.baseColorFactor.size() == 4)
      mat.base_color = glm::vec4(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2], pbr.baseColorFactor[3]);
    mat.base_color_texture = texture(pbr.baseColorTexture.index, true, gm.name);
    mat.roughness = static_cast<float>(pbr.roughnessFactor);
    mat.emissive = vec3_or(gm.emissiveFactor, glm::vec3(0));
    if (auto it = gm.extensions.find("KHR_materials_emissive_strength"); it != gm.extensions.end() && it->second.Has("emissiveStrength"))
      mat.emissive *= static_cast<float>(it->second.Get("emissiveStrength").GetNumberAsDouble());
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
    }
    return mat;
  }

  void visit(int node_index, const glm::mat4& parent, int depth) {
    if (node_index < 0 || node_index >= static_cast<int>(m_.nodes.size()))
      throw Error(s_.path.string() + ": node " + std::to_string(node_index) + " does not exist");
    if (depth > 64) throw Error(s_.path.string() + ": the node hierarchy is deeper than 64 (a cycle?)");
    const auto& node = m_.nodes[node_index];
    glm::mat4 world = parent * local_matrix(node);
    std::string name = node.name.empty() ? "node" + std::to_string(node_index) : node.name;
    if (node.mesh >= 0) add_instance(node, name, world);
    if (node.camera >= 0) add_camera(node, name, world);
    if (node.extras.Has("lightpass"))
      s_.node_extras.push_back({.name = name, .world = world, .lightpass_json = json_text(node.extras.Get("lightpass")).dump()});
    if (auto it = node.extensions.find("KHR_lights_punctual"); it != node.extensions.end() && it->second.Has("light"))
      add_light(it->second.Get("light").GetNumberAsInt(), name, world);
    for (int child : node.children) visit(child, world, depth + 1);
  }

  void add_instance(const tinygltf::Node& node, const std::string& name, const glm::mat4& world) {
    if (node.mesh >= static_cast<int>(m_.meshes.size()))
      throw Error(s_.path.string() + ": node '" + name + "' uses mesh " + std::to_string(node.mesh) + ", which does not exist");
    if (mesh_of_gltf_[node.mesh] < 0) mesh_of_gltf_[node.mesh] = mesh(node.mesh);
    Instance inst{.name = name, .mesh = mesh_of_gltf_[node.mesh], .model = world};
    if (node.extras.Has("lightpass")) {
      const auto& e = node.extras.Get("lightpass");
      std::string shape = e.Has("shape") ? e.Get("shape").Get<std::string>() : "";
      if (shape == "sphere" && e.Has("radius")) {
        inst.shape.kind = Shape::Sphere;
        inst.shape.radius = static_cast<float>(e.Get("radius").GetNumberAsDouble());
      } else if (shape == "rect" && e.Has("size") && e.Get("size").ArrayLen() == 2) {
        inst.shape.kind = Shape::Rect;
        inst.shape.size = {e.Get("size").Get(0).GetNumberAsDouble(), e.Get("size").Get(1).GetNumberAsDouble()};
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
      if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) {
        warn(where + ": mode " + std::to_string(prim.mode) + " is not triangles; skipped");
        continue;
      }
      out.primitives.push_back(primitive(prim, where));
    }
    s_.meshes.push_back(std::move(out));
    return static_cast<int>(s_.meshes.size() - 1);
  }

  Primitive primitive(const tinygltf::Primitive& prim, const std::string& where) {
    auto attr = [&](const char* name) { auto it = prim.attributes.find(name); return it == prim.attributes.end() ? -1 : it->second; };
    if (attr("POSITION") < 0) throw Error(where + ": no POSITION attribute");
    AccessorReader pos(m_, attr("POSITION"), where + " POSITION");
    const size_t base = s_.vertices.size(), n = pos.count();
    s_.vertices.resize(base + n);
    for (size_t i = 0; i < n; ++i) s_.vertices[base + i].position = pos.vec<3>(i);
    auto read = [&](const char* name, auto assign) {
      if (attr(name) < 0) return false;
      AccessorReader r(m_, attr(name), where + " " + name);
      if (r.count() != n) throw Error(where + ": " + name + " has " + std::to_string(r.count()) + " elements but POSITION has " + std::to_string(n));
      for (size_t i = 0; i < n; ++i) assign(s_.vertices[base + i], r, i);
      return true;
    };
    bool has_normal = read("NORMAL", [](Vertex& v, const AccessorReader& r, size_t i) { v.normal = glm::normalize(r.vec<3>(i)); });
    bool has_uv = read("TEXCOORD_0", [](Vertex& v, const AccessorReader& r, size_t i) { v.uv = r.vec<2>(i); });
    bool has_tangent = read("TANGENT", [](Vertex& v, const AccessorReader& r, size_t i) { v.tangent = r.vec<4>(i); });

    Primitive out;
    out.first_index = static_cast<std::uint32_t>(s_.indices.size());
    if (prim.indices >= 0) {
      AccessorReader idx(m_, prim.indices, where + " indices");
      for (size_t i = 0; i < idx.count(); ++i) {
        std::uint32_t k = idx.index(i);
        if (k >= n) throw Error(where + ": index " + std::to_string(k) + " (at position " + std::to_string(i) +
                                ") is past the " + std::to_string(n) + " vertices");
        s_.indices.push_back(static_cast<std::uint32_t>(base + k));
      }
    } else {
      for (size_t i = 0; i < n; ++i) s_.indices.push_back(static_cast<std::uint32_t>(base + i));
    }
    out.index_count = static_cast<std::uint32_t>(s_.indices.size() - out.first_index);
    if (out.index_count % 3) throw Error(where + ": " + std::to_string(out.index_count) + " indices is not a whole number of triangles");
    out.material = prim.material >= 0 && prim.material < default_material_ ? prim.material : default_material_;
    if (!has_normal) generate_normals(s_.vertices, s_.indices, out.first_index, out.index_count);
    if (!has_tangent) generate_tangents(s_.vertices, s_.indices, out.first_index, out.index_count, has_uv);
    return out;
  }

  void add_camera(const tinygltf::Node& node, const std::string& name, const glm::mat4& world) {
    if (node.camera >= static_cast<int>(m_.cameras.size())) throw Error(s_.path.string() + ": node '" + name + "' uses a camera that does not exist");
    const auto& c = m_.cameras[node.camera];
    if (c.type != "perspective") {
      warn("camera '" + name + "' is " + c.type + "; only perspective cameras are used");
      return;
    }
    Camera cam{.name = name, .world = world, .yfov = float(c.perspective.yfov), .znear = float(c.perspective.znear),
               .zfar = c.perspective.zfar > 0 ? float(c.perspective.zfar) : 1000.f};
    // Remove any scale from the node so view() is a rigid transform.
    for (int i = 0; i < 3; ++i) cam.world[i] = glm::vec4(glm::normalize(glm::vec3(cam.world[i])), 0);
    s_.cameras.push_back(cam);
  }

  void add_light(int index, const std::string& name, const glm::mat4& world) {
    if (index < 0 || index >= static_cast<int>(m_.lights.size()))
      throw Error(s_.path.string() + ": node '" + name + "' uses light " + std::to_string(index) + ", which does not exist");
    const auto& gl = m_.lights[index];
    Light l;
    l.name = gl.name.empty() ? name : gl.name;
    l.color = vec3_or(gl.color, glm::vec3(1));
    l.intensity = static_cast<float>(gl.intensity);
    l.range = static_cast<float>(gl.range);
    l.position = glm::vec3(world[3]);
    l.direction = glm::normalize(-glm::vec3(world[2]));
    if (gl.type == "directional") l.type = LightType::Directional;
    else if (gl.type == "point") l.type = LightType::Point;
    else if (gl.type == "spot") {
      l.type = LightType::Spot;
      l.inner_cone = static_cast<float>(gl.spot.innerConeAngle);
      l.outer_cone = static_cast<float>(gl.spot.outerConeAngle);
    } else {
      warn("light '" + l.name + "' has unknown type '" + gl.type + "'; skipped");
      return;
    }
    s_.lights.push_back(l);
  }

  void compute_bounds() {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const auto& inst : s_.instances)
      for (const auto& p : s_.meshes[inst.mesh].primitives)
        for (std::uint32_t i = p.first_index; i < p.first_index + p.index_count; ++i) {
          glm::vec3 w = glm::vec3(inst.model * glm::vec4(s_.vertices[s_.indices[i]].position, 1));
          lo = glm::min(lo, w);
          hi = glm::max(hi, w);
        }
    s_.bounds_min = lo;
    s_.bounds_max = hi;
  }

  void warn(const std::string& w) { s_.warnings.push_back(w); }

  const tinygltf::Model& m_;
  Scene& s_;
  int default_material_ = 0;
  std::vector<int> mesh_of_gltf_;
  std::vector<std::pair<int, bool>> texture_keys_;
};

}  // namespace

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
    if (glm::length(t) < 1e-6f) {
      // No usable UVs: any unit vector perpendicular to the normal will do.
      glm::vec3 axis = std::abs(x.normal.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
      t = glm::cross(axis, x.normal);
    }
    t = glm::normalize(t);
    // glTF: bitangent = cross(N, T) * w points up the image, i.e. towards -v (v runs down).
    float w = glm::dot(glm::cross(x.normal, t), bitangent[idx[i]]) > 0 ? -1.f : 1.f;
    x.tangent = glm::vec4(t, w);
  }
}

Scene load_scene(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) throw Error("cannot open scene '" + path.string() + "': no such file");
  if (std::filesystem::file_size(path) == 0) throw Error("cannot load scene '" + path.string() + "': the file is empty");
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  bool binary = path.extension() == ".glb";
  bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path.string())
                   : loader.LoadASCIIFromFile(&model, &err, &warn, path.string());
  if (!ok) {
    while (!err.empty() && err.back() == '\n') err.pop_back();
    throw Error("cannot load scene '" + path.string() + "': " + (err.empty() ? "not valid glTF" : err));
  }
  Scene scene;
  scene.path = path;
  Loader(model, scene).load();
  return scene;
}

}  // namespace lp
