// Builds one glTF 2.0 scene (.gltf JSON + one .bin buffer) the way the lightpass loader
// expects it: flat node list (every node a scene root), separate tightly packed bufferViews per
// attribute, KHR_lights_punctual lights, KHR_materials_specular on every material, named
// perspective cameras, and `extras.lightpass` on the scene (ambient) and on analytic shapes.
// Output is deterministic: keys sorted (nlohmann::json's std::map), floats written with the
// shortest representation that reads back to the same float32.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "mesh.h"

namespace scenegen {

using nlohmann::json;

// Float -> JSON number that prints as the shortest decimal that rounds back to this float.
double fnum(float v);
json jvec(const glm::vec2& v);
json jvec(const glm::vec3& v);
json jvec(const glm::vec4& v);
json jquat(const glm::quat& q);  // glTF order [x, y, z, w], w >= 0

// Rotation taking the node's -Z (its view / light direction) to `forward`, +Y towards `up`.
glm::quat look_rotation(const glm::vec3& forward, const glm::vec3& up = glm::vec3(0, 1, 0));
// Rotation from a face frame (see face_frame in mesh.h).
glm::quat frame_rotation(const glm::mat3& frame);

// Deterministic, readable JSON text: objects one key per line, arrays of scalars on one line.
std::string format_json(const json& j);

struct Material {
  std::string name;
  glm::vec4 base_color{1.0f};
  int base_color_texture = -1;
  float metallic = 0.0f;
  float roughness = 0.5f;
  glm::vec3 emissive{0.0f};
  int normal_texture = -1;
  glm::vec3 specular_color{0.5f};
  float specular = 1.0f;
  // glTF alphaMode: "" writes none (OPAQUE, every scene before chapter 10), "BLEND" for glass
  // (chapter 10 draws those surfaces after the deferred passes, blended by base_color.a).
  std::string alpha_mode;
};

enum class IndexType { Auto, U16, U32 };

class GltfBuilder {
 public:
  explicit GltfBuilder(std::string name);

  const std::string& name() const { return name_; }
  void set_ambient(const glm::vec3& ambient) { ambient_ = ambient; }
  // Another key of the scene's extras.lightpass (beside "ambient"), e.g. chapter 06's sun scale.
  void set_scene_extra(const std::string& key, const json& value) { scene_extras_[key] = value; }

  int add_material(const Material& m);
  // An image file next to the .gltf and a texture using it (repeat wrap, trilinear filtering).
  int add_texture(const std::string& uri);
  int add_mesh(const std::string& name, const Mesh& mesh, int material, IndexType index_type = IndexType::Auto);

  // Nodes. Every node is a root of the scene, in the order added.
  int add_node(json node);
  int add_mesh_node(const std::string& name, int mesh, const glm::vec3& translation,
                    const std::optional<glm::quat>& rotation = std::nullopt, const json& lightpass_extras = nullptr);
  // Sphere of `radius` centred at `centre`: mesh generated in local space, node translation only.
  int add_sphere_node(const std::string& name, int mesh, const glm::vec3& centre, float radius);
  // Rect (local XZ plane, normal +Y, centred at the node origin) of size sx x sz.
  int add_rect_node(const std::string& name, int mesh, const glm::vec3& centre, const glm::mat3& frame, float sx, float sz);

  int add_camera(const std::string& name, const glm::vec3& eye, const glm::vec3& target, float yfov,
                 float znear, float zfar, const glm::vec3& up = glm::vec3(0, 1, 0));
  int add_point_light(const std::string& name, const glm::vec3& position, const glm::vec3& color, float candela,
                      float range = 0.0f);
  int add_spot_light(const std::string& name, const glm::vec3& position, const glm::vec3& direction,
                     const glm::vec3& color, float candela, float inner, float outer, float range = 0.0f);
  int add_directional_light(const std::string& name, const glm::vec3& direction, const glm::vec3& color, float lux);

  // The whole document; `buffer_uri` defaults to <name>.bin.
  json document(const std::string& buffer_uri = "") const;
  const std::vector<uint8_t>& binary() const { return bin_; }
  // Writes dir/<name>.gltf and dir/<name>.bin.
  void write(const std::filesystem::path& dir) const;

 private:
  int add_view(const void* data, size_t bytes, int target);
  int add_accessor(int view, int component_type, size_t count, const char* type, const json& min = nullptr,
                   const json& max = nullptr);
  int add_light(json light, const glm::vec3& position, const std::optional<glm::quat>& rotation);

  std::string name_;
  glm::vec3 ambient_{0.03f, 0.03f, 0.035f};
  json scene_extras_ = json::object();
  std::vector<uint8_t> bin_;
  json buffer_views_ = json::array(), accessors_ = json::array(), meshes_ = json::array();
  json materials_ = json::array(), textures_ = json::array(), images_ = json::array();
  json nodes_ = json::array(), cameras_ = json::array(), lights_ = json::array();
};

}  // namespace scenegen
