#pragma once
// A glTF 2.0 scene flattened into what the chapters draw: one vertex and one index array,
// materials, textures, instances with world matrices, KHR_lights_punctual lights and the
// named cameras. CPU side only (the ground-truth renderers read it too); scene_gpu.h uploads it.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "common/image.h"

namespace lp {

struct Vertex {
  glm::vec3 position{0};
  glm::vec3 normal{0, 1, 0};
  glm::vec2 uv{0};
  glm::vec4 tangent{1, 0, 0, 1};  // xyz tangent, w = handedness of the bitangent
};

struct Primitive {
  std::uint32_t first_index = 0, index_count = 0;  // into Scene::indices (already rebased)
  int material = 0;
};

struct Mesh {
  std::string name;
  std::vector<Primitive> primitives;
};

// Exactly what the file says, in glTF's terms; the chapters map it onto their lighting model.
struct Material {
  std::string name;
  glm::vec4 base_color{1};
  int base_color_texture = -1;  // index into Scene::textures (sRGB)
  glm::vec3 emissive{0};
  glm::vec3 specular_color{1};  // KHR_materials_specular: specularColorFactor * specularFactor
  float specular_factor = 1;
  bool has_specular_extension = false;
  float roughness = 1;
  int normal_texture = -1;      // index into Scene::textures (linear)
  float normal_scale = 1;
  int emissive_texture = -1;    // index into Scene::textures (sRGB); emitted = emissive * texel
  bool double_sided = false;    // glTF doubleSided: no back-face culling, the normal flips behind
  // alphaMode BLEND: drawn over the opaque image, covering base_color.a of what lies behind
  // (chapter 10). The deferred G-buffer skips these surfaces (SceneGpu::Primitives::Opaque).
  bool blend = false;
};

struct Texture {
  std::string name;
  ImageRGBA8 image;
  bool srgb = false;
  bool fallback = false;  // the file could not be read: a checker stands in
};

enum class LightType { Directional, Point, Spot };

struct Light {
  std::string name;
  LightType type = LightType::Point;
  glm::vec3 color{1};
  float intensity = 1;        // candela (point, spot) or lux (directional)
  glm::vec3 position{0};      // world space
  glm::vec3 direction{0, 0, -1};  // world space, the way the light shines
  float range = 0;            // 0: unbounded
  float inner_cone = 0, outer_cone = 0.7853982f;  // radians
  // The light node's extras {"lightpass": {"casts_shadows": true | false}}; unset where the file
  // does not say, and a chapter's default applies (chapter 06: only the sun, the first
  // directional light, casts).
  std::optional<bool> casts_shadows;
};

// [light-defect]
// Why a light cannot be used, or nothing: the one rule for every chapter. The loader leaves
// such a light out, by name; chapter 03's light set does the same with a light made in code.
// A light that is valid but gives no light (zero intensity or colour) is not a defect.
std::optional<std::string> light_defect(const Light& light);
// [/light-defect]

struct Camera {
  std::string name;
  glm::mat4 world{1};  // camera-to-world; the camera looks down -Z
  float yfov = 0.8f, znear = 0.1f, zfar = 1000.f;
  glm::mat4 view() const { return glm::inverse(world); }
  glm::vec3 position() const { return glm::vec3(world[3]); }
};

// Exact geometry a mesh stands for, from node extras {"lightpass": {"shape": ...}}, so a
// ground-truth renderer can intersect the true surface rather than its triangles.
struct Shape {
  enum Kind { None, Sphere, Rect } kind = None;
  float radius = 0;      // Sphere, centred at the node origin
  glm::vec2 size{0};     // Rect in the node's XZ plane, normal +Y
};

struct Instance {
  std::string name;
  int mesh = -1;
  glm::mat4 model{1};
  Shape shape;
};

// A node's `"extras": {"lightpass": {...}}`, kept as JSON text for what a chapter defines
// itself (chapter 04 reads its neon lights from it). Every node that has one, mesh or not.
struct NodeExtras {
  std::string name;
  glm::mat4 world{1};
  std::string lightpass_json;  // the object under "lightpass", serialised
};

struct Scene {
  std::filesystem::path path;
  std::vector<Vertex> vertices;
  std::vector<std::uint32_t> indices;
  std::vector<Mesh> meshes;
  std::vector<Material> materials;  // never empty: a default grey material is appended last
  std::vector<Texture> textures;
  std::vector<Instance> instances;
  std::vector<Light> lights;
  std::vector<Camera> cameras;      // in node order; the first is the default view
  std::vector<NodeExtras> node_extras;  // in node order
  glm::vec3 ambient{0};             // scene extras {"lightpass": {"ambient": [r,g,b]}}
  // The scene's extras.lightpass, serialised ("{}" when it has none), for what a chapter
  // defines itself (chapter 06 reads the sun scale the scene asks for).
  std::string lightpass_json = "{}";
  glm::vec3 bounds_min{0}, bounds_max{0};
  std::vector<std::string> warnings;
  std::vector<std::string> notes;   // what the loader supplied: an automatic view, default lights

  // The named camera; throws Error listing the names when there is none of that name.
  const Camera& camera(const std::string& name) const;
};

// What a hostile or huge file may cost before it is refused with a message that names the
// limit (a DAG of nodes that list the same children can expand exponentially). The fuzz
// target passes smaller ones: it explores the checks, not the scale.
struct SceneLimits {
  std::size_t max_file_bytes = std::size_t(1) << 30;      // the .gltf/.glb and each .bin
  std::size_t max_instances = 1'000'000;                 // mesh nodes after expansion
  std::size_t max_node_visits = 4'000'000;                // nodes visited, meshes or not
  std::size_t max_lights = 100'000;                      // light nodes after expansion
  std::size_t max_cameras = 10'000;                      // camera nodes after expansion
  // The lights' work: each light counts the share of the scene its range reaches (1 without a
  // range, as for the sun), for a frame shades every pixel a light reaches.
  double max_light_reach = 4096;
  std::size_t max_node_extras = 100'000;                  // nodes with extras.lightpass
  std::size_t max_name_bytes = std::size_t(1) << 28;      // names and extras copied (256 MiB)
  std::size_t max_vertices = std::size_t(1) << 26;       // 64 M vertices (3 GiB)
  std::size_t max_indices = std::size_t(1) << 28;        // 256 M indices (1 GiB)
  int max_image_side = 32768;                             // texels, either side
  std::size_t max_image_texels = std::size_t(1) << 26;    // 64 M texels per image
  std::size_t max_total_texels = std::size_t(1) << 28;    // 256 M texels (1 GiB decoded) for all images, each
                                                          // distinct file counted once
};

// The name of the view the loader adds after the file's own cameras (framing the bounds).
inline constexpr const char* kAutoView = "auto";

// Throws Error with the file and what is wrong (malformed JSON, missing buffer, an index past
// the vertices, an unsupported required extension, a degenerate camera, a limit exceeded,
// ...). Missing textures are not errors: a checker stands in, with a warning. Missing normals
// are generated flat, missing tangents from the UVs. A scene without cameras gets a view
// framing its bounds, one without lights a default rig (each said in Scene::notes).
Scene load_scene(const std::filesystem::path& path, const SceneLimits& limits = {});
// The same from bytes already in memory (a .gltf's JSON or a .glb, told apart by content);
// `path` names the file in messages and its folder is where relative URIs are found.
// Needs no GL context (the fuzz target calls it).
Scene load_scene_from_memory(const std::vector<unsigned char>& bytes, const std::filesystem::path& path,
                             const SceneLimits& limits = {});

// Fills in normals (area-weighted over the triangles that share a vertex: flat for triangles
// that share none) and tangents (from UVs, or any perpendicular without UVs).
void generate_normals(std::vector<Vertex>& v, const std::vector<std::uint32_t>& indices, std::uint32_t first, std::uint32_t count);
void generate_tangents(std::vector<Vertex>& v, const std::vector<std::uint32_t>& indices, std::uint32_t first, std::uint32_t count, bool has_uv);

}  // namespace lp
