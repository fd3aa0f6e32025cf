// The four scenes of the book. Every scene: cameras first (the first camera is the default
// view), then lights, then geometry; every node a root. Units are metres, Y is up.
//
// Exposure: the chapters 1-4 renderers write linear radiance = albedo * E (+ specular) straight
// to 8-bit sRGB, E being the irradiance sum of I/d^2 * N.L (glTF range window) over the
// lights. Intensities are chosen so that lit surfaces get E of roughly 0.2 .. 1.0;
// `scenegen --verify` prints the irradiance the lights give on the analytic shapes.
#include "scenes.h"

#include <charconv>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <string>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "gltf_writer.h"
#include "mesh.h"
#include "rng.h"
#include "textures.h"

namespace scenegen {

namespace fs = std::filesystem;

namespace {

constexpr float kPi = std::numbers::pi_v<float>;
const glm::vec3 kUp(0, 1, 0);

fs::path fresh_dir(const fs::path& out, const std::string& name) {
  const fs::path dir = out / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string num_text(float v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string padded(int v, int width) {
  std::string s = std::to_string(v);
  while (static_cast<int>(s.size()) < width) s = "0" + s;
  return s;
}

Material matte(std::string name, glm::vec3 color, float roughness, float specular_grey) {
  Material m;
  m.name = std::move(name);
  m.base_color = glm::vec4(color, 1.0f);
  m.roughness = roughness;
  m.specular_color = glm::vec3(specular_grey);
  return m;
}

// Tinted glass (chapter 10): alphaMode BLEND, alpha = the share of light the surface takes.
Material glass_material(std::string name, glm::vec3 color, float alpha, float roughness) {
  Material m = matte(std::move(name), color, roughness, 0.5f);
  m.base_color.a = alpha;
  m.alpha_mode = "BLEND";
  return m;
}

Material emitter(std::string name, glm::vec3 base, glm::vec3 emissive) {
  Material m = matte(std::move(name), base, 0.6f, 0.2f);
  m.emissive = emissive;
  return m;
}

glm::mat4 place(const glm::vec3& t, const glm::mat3& r = glm::mat3(1.0f)) {
  glm::mat4 m(r);
  m[3] = glm::vec4(t, 1.0f);
  return m;
}

glm::mat3 yaw(float radians) { return glm::mat3(glm::rotate(glm::mat4(1.0f), radians, kUp)); }

glm::vec3 hsv(float h, float s, float v) {
  const float hh = std::fmod(h, 1.0f) * 6.0f;
  const int sector = static_cast<int>(hh);
  const float f = hh - static_cast<float>(sector);
  const float p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  switch (sector) {
    case 0: return {v, t, p};
    case 1: return {q, v, p};
    case 2: return {p, v, t};
    case 3: return {p, q, v};
    case 4: return {t, p, v};
    default: return {v, p, q};
  }
}

// One rect mesh per distinct size (1 texture repeat per metre unless uv_scale is given).
class RectMeshes {
 public:
  RectMeshes(GltfBuilder& b) : b_(b) {}
  int get(float sx, float sz, int material, glm::vec2 uv_scale = glm::vec2(0.0f), int div_x = 1, int div_z = 1) {
    if (uv_scale == glm::vec2(0.0f)) uv_scale = {sx, sz};
    const auto key = std::make_tuple(sx, sz, material, uv_scale.x, uv_scale.y, div_x, div_z);
    if (auto it = cache_.find(key); it != cache_.end()) return it->second;
    const std::string name = "rect_" + num_text(sx) + "x" + num_text(sz) + "_m" + std::to_string(material);
    const int mesh = b_.add_mesh(name, make_rect(sx, sz, div_x, div_z, uv_scale), material);
    cache_[key] = mesh;
    return mesh;
  }
  // A rect node; the mesh is shared between rects of the same size and material.
  int node(const std::string& name, const glm::vec3& centre, const glm::vec3& normal, const glm::vec3& x_axis,
           float sx, float sz, int material, glm::vec2 uv_scale = glm::vec2(0.0f), int div_x = 1, int div_z = 1) {
    return b_.add_rect_node(name, get(sx, sz, material, uv_scale, div_x, div_z), centre, face_frame(normal, x_axis), sx, sz);
  }

 private:
  GltfBuilder& b_;
  std::map<std::tuple<float, float, int, float, float, int, int>, int> cache_;
};

// A neon node (chapter 04, see chapters/04_neon/neon_scene.h): the tube along the node's
// local X through `centre`, the first barn door along local +Y (`up` made perpendicular).
void add_neon(GltfBuilder& b, const std::string& name, glm::vec3 centre, glm::vec3 along, glm::vec3 up, json tube) {
  const glm::vec3 x = glm::normalize(along);
  const glm::vec3 y = glm::normalize(up - glm::dot(up, x) * x);
  const glm::quat q = frame_rotation(glm::mat3(x, y, glm::cross(x, y)));
  json node = {{"name", name}, {"translation", jvec(centre)}, {"extras", {{"lightpass", {{"neon", tube}}}}}};
  if (std::fabs(q.w) < 1.0f - 1e-7f) node["rotation"] = jquat(q);
  b.add_node(node);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// forward: chapter 01, per-vertex vs per-pixel Blinn-Phong on spheres of growing tessellation.
void write_forward(const fs::path& out) {
  const fs::path dir = fresh_dir(out, "forward");
  GltfBuilder b("forward");
  b.set_ambient({0.03f, 0.03f, 0.035f});

  const int tess[5] = {8, 16, 32, 64, 128};
  const float radius = 0.8f;
  auto centre = [&](int i) { return glm::vec3(-4.0f + 2.0f * static_cast<float>(i), radius, 0.0f); };

  b.add_camera("overview", {0.0f, 4.0f, 9.0f}, {0.0f, 0.6f, 0.0f}, 0.7f, 0.05f, 100.0f);
  for (int i = 0; i < 5; ++i)  // same offset from every sphere: the close-ups are comparable
    b.add_camera("close_" + std::to_string(tess[i]), centre(i) + glm::vec3(0.0f, 0.6f, 3.2f), centre(i), 0.6f, 0.05f, 100.0f);
  b.add_camera("grazing", {-5.8f, 0.3f, 2.5f}, {5.0f, 0.45f, -0.8f}, 0.7f, 0.05f, 100.0f);

  b.add_directional_light("sun", {0.75f, -0.35f, -0.55f}, {1.0f, 0.82f, 0.6f}, 0.5f);
  b.add_point_light("point_blue", {-3.0f, 2.2f, 2.0f}, {0.35f, 0.55f, 1.0f}, 3.0f);
  b.add_point_light("point_orange", {3.0f, 2.2f, 2.0f}, {1.0f, 0.55f, 0.2f}, 3.0f);
  b.add_spot_light("spot_white", {0.0f, 5.0f, 3.5f}, glm::vec3(0.0f, 0.4f, 0.0f) - glm::vec3(0.0f, 5.0f, 3.5f),
                   {1.0f, 1.0f, 1.0f}, 15.0f, 0.25f, 0.4f);

  const uint8_t dark[3] = {110, 110, 110}, light[3] = {200, 200, 200};
  write_png(dir / "checker.png", make_checker(512, 8, dark, light));
  Material ground = matte("ground_checker", glm::vec3(1.0f), 0.7f, 0.2f);
  ground.base_color_texture = b.add_texture("checker.png");
  const int ground_mat = b.add_material(ground);
  // 32 x 32 quads so per-vertex lighting of the floor is not absurd; 24 x 24 checks of 0.5 m.
  b.add_rect_node("ground", b.add_mesh("ground", make_rect(12.0f, 12.0f, 32, 32, {3.0f, 3.0f}), ground_mat),
                  glm::vec3(0.0f), glm::mat3(1.0f), 12.0f, 12.0f);

  const struct {
    const char* name;
    glm::vec3 color;
    float roughness;
  } looks[5] = {
      {"glossy_red", {0.8f, 0.1f, 0.08f}, 0.25f},   {"glossy_gold", {0.85f, 0.55f, 0.1f}, 0.3f},
      {"glossy_green", {0.15f, 0.6f, 0.2f}, 0.35f}, {"glossy_blue", {0.1f, 0.3f, 0.85f}, 0.4f},
      {"glossy_violet", {0.6f, 0.2f, 0.7f}, 0.3f},
  };
  for (int i = 0; i < 5; ++i) {
    const int mat = b.add_material(matte(looks[i].name, looks[i].color, looks[i].roughness, 0.5f));
    const std::string name = "sphere_" + std::to_string(tess[i]);
    const int mesh = b.add_mesh(name, make_uv_sphere(radius, tess[i], tess[i] / 2), mat,
                                tess[i] >= 64 ? IndexType::U32 : IndexType::U16);
    b.add_sphere_node(name, mesh, centre(i), radius);
  }
  b.write(dir);
}

// ---------------------------------------------------------------------------------------------
// atrium: columns, arches, walls, a tiled floor with a normal map; 8 point lights + the sun.
void write_atrium(const fs::path& out) {
  const fs::path dir = fresh_dir(out, "atrium");
  GltfBuilder b("atrium");
  b.set_ambient({0.03f, 0.03f, 0.035f});
  // Beside the eight point lights the sun's 0.4 lux shows its shadows only faintly: the scene
  // asks chapter 06, which shows them, for 4 times its sun (an atrium setting, not the chapter's).
  b.set_scene_extra("shadows_sun_scale", 4);

  b.add_camera("overview", {0.0f, 10.0f, 17.0f}, {0.0f, 1.5f, -3.0f}, 0.8f, 0.1f, 100.0f);
  b.add_camera("aisle", {0.0f, 1.7f, 11.5f}, {0.0f, 2.2f, -12.0f}, 0.9f, 0.05f, 100.0f);
  b.add_camera("corner", {7.3f, 1.8f, 11.3f}, {-2.0f, 2.0f, -6.0f}, 0.9f, 0.05f, 100.0f);

  b.add_directional_light("sun", {-0.4f, -1.0f, -0.3f}, {1.0f, 0.95f, 0.85f}, 0.4f);
  const float aisle_z[4] = {-9.0f, -3.0f, 3.0f, 9.0f};
  for (int i = 0; i < 4; ++i)
    b.add_point_light("aisle_" + std::to_string(i), {0.0f, 3.2f, aisle_z[i]}, {1.0f, 0.9f, 0.75f}, 5.0f);
  const struct {
    const char* name;
    glm::vec3 pos, color;
  } nave[4] = {
      {"nave_teal", {-6.2f, 2.4f, -6.0f}, {0.3f, 0.9f, 0.8f}},
      {"nave_amber", {6.2f, 2.4f, -6.0f}, {1.0f, 0.6f, 0.2f}},
      {"nave_rose", {-6.2f, 2.4f, 6.0f}, {1.0f, 0.4f, 0.55f}},
      {"nave_violet", {6.2f, 2.4f, 6.0f}, {0.6f, 0.45f, 1.0f}},
  };
  for (const auto& l : nave) b.add_point_light(l.name, l.pos, l.color, 2.5f);

  Image albedo, normal;
  make_tiles(512, 4, albedo, normal);
  write_png(dir / "tiles_albedo.png", albedo);
  write_png(dir / "tiles_normal.png", normal);
  Material floor = matte("floor_tiles", glm::vec3(1.0f), 0.35f, 0.5f);
  floor.base_color_texture = b.add_texture("tiles_albedo.png");
  floor.normal_texture = b.add_texture("tiles_normal.png");
  const int floor_mat = b.add_material(floor);
  const int plaster = b.add_material(matte("plaster", {0.75f, 0.7f, 0.62f}, 0.8f, 0.1f));
  const int stone = b.add_material(matte("stone", {0.8f, 0.78f, 0.72f}, 0.55f, 0.3f));

  RectMeshes rects(b);
  // Floor 16 x 24 m, 1 m tiles (the texture holds 4 x 4 tiles).
  rects.node("floor", {0, 0, 0}, kUp, {1, 0, 0}, 16.0f, 24.0f, floor_mat, {4.0f, 6.0f});
  const float wall_h = 7.0f;
  rects.node("wall_left", {-8.0f, wall_h / 2, 0.0f}, {1, 0, 0}, {0, 0, -1}, 24.0f, wall_h, plaster);
  rects.node("wall_right", {8.0f, wall_h / 2, 0.0f}, {-1, 0, 0}, {0, 0, 1}, 24.0f, wall_h, plaster);
  rects.node("wall_back", {0.0f, wall_h / 2, -12.0f}, {0, 0, 1}, {1, 0, 0}, 16.0f, wall_h, plaster);

  // Column: plinth, shaft, capital; its top (y = 4) carries the arch ends.
  Mesh column;
  column.append(make_box({0.9f, 0.25f, 0.9f}), place({0.0f, 0.125f, 0.0f}));
  column.append(make_cylinder(0.32f, 3.5f, 32, {2.0f, 3.5f}), place({0.0f, 0.25f, 0.0f}));
  column.append(make_box({0.9f, 0.25f, 0.9f}), place({0.0f, 3.875f, 0.0f}));
  const int column_mesh = b.add_mesh("column", column, stone);
  // Arch: half torus spanning two columns 3 m apart, turned into the YZ plane.
  const int arch_mesh = b.add_mesh("arch", make_half_torus(1.5f, 0.22f, 32, 16, {4.0f, 1.0f}), stone);
  const glm::quat arch_rot = glm::angleAxis(kPi / 2, kUp);
  for (int side = 0; side < 2; ++side) {
    const float x = side == 0 ? -4.0f : 4.0f;
    const std::string s = side == 0 ? "l" : "r";
    for (int k = 0; k < 7; ++k)
      b.add_mesh_node("column_" + s + std::to_string(k), column_mesh, {x, 0.0f, -9.0f + 3.0f * static_cast<float>(k)});
    for (int k = 0; k < 6; ++k)
      b.add_mesh_node("arch_" + s + std::to_string(k), arch_mesh, {x, 4.0f, -7.5f + 3.0f * static_cast<float>(k)}, arch_rot);
  }
  b.write(dir);
}

// ---------------------------------------------------------------------------------------------
// street: night street, 300 small coloured point lights with ranges, 12 street lamps.
// build_street() fills a builder (street_neon adds to it); `cameras_first` adds cameras before
// the street's own, so that the first of them is the default view.
namespace {
void build_street(GltfBuilder& b, const std::function<void(GltfBuilder&)>& cameras_first) {
  b.set_ambient({0.015f, 0.015f, 0.02f});
  Pcg32 rng(0x57ee7u);

  // The point lights first (drawn from the RNG), so the cameras can refer to one of them.
  struct PointLight {
    glm::vec3 pos, color;
    float intensity, range;
  };
  std::vector<PointLight> points;
  for (int i = 0; i < 300; ++i) {
    PointLight p;
    p.pos = {rng.range(-7.0f, 7.0f), rng.range(1.0f, 3.2f), rng.range(-57.0f, 57.0f)};
    p.color = hsv(rng.uniform(), rng.range(0.55f, 0.9f), 1.0f);
    p.intensity = rng.range(0.3f, 1.0f);
    points.push_back(p);
  }
  // point_000 is the light the `inside_light` camera sits in.
  points[0].pos = {1.5f, 1.8f, 22.0f};
  points[0].color = {1.0f, 0.85f, 0.7f};
  points[0].intensity = 0.8f;
  for (auto& p : points) p.range = std::sqrt(p.intensity / 0.015f);  // I / d^2 = 0.015 at the range

  if (cameras_first) cameras_first(b);
  b.add_camera("overview", {0.0f, 60.0f, 100.0f}, {0.0f, 0.0f, 0.0f}, 0.9f, 0.5f, 400.0f);
  b.add_camera("street_level", {2.0f, 1.7f, 55.0f}, {0.0f, 3.0f, -40.0f}, 0.9f, 0.05f, 200.0f);
  b.add_camera("inside_light", points[0].pos + glm::vec3(0.5f, 0.0f, 1.5f), {0.0f, 2.0f, -30.0f}, 0.9f, 0.05f, 200.0f);
  b.add_camera("far", {0.0f, 10.0f, 190.0f}, {0.0f, 3.0f, 0.0f}, 0.5f, 0.5f, 500.0f);

  b.add_directional_light("moon", {0.3f, -1.0f, 0.4f}, {0.55f, 0.65f, 1.0f}, 0.08f);
  for (size_t i = 0; i < points.size(); ++i)
    b.add_point_light("point_" + padded(static_cast<int>(i), 3), points[i].pos, points[i].color, points[i].intensity,
                      points[i].range);

  // Street lamps: poles on the kerbs, arms over the road, spots pointing straight down.
  const float lamp_z[6] = {-50.0f, -30.0f, -10.0f, 10.0f, 30.0f, 50.0f};
  const float pole_x = 5.6f, arm = 1.15f;
  for (int side = 0; side < 2; ++side) {
    const float sign = side == 0 ? -1.0f : 1.0f;  // left row at -x
    for (int k = 0; k < 6; ++k) {
      const float z = lamp_z[k] + (side == 0 ? 0.0f : 10.0f) - 5.0f;
      const glm::vec3 head(sign * (pole_x - arm), 5.75f, z);
      b.add_spot_light("spot_" + std::string(side == 0 ? "l" : "r") + std::to_string(k), head, {0, -1, 0},
                       {1.0f, 0.85f, 0.6f}, 25.0f, 0.45f, 0.75f, 18.0f);
    }
  }

  const int asphalt = b.add_material(matte("asphalt", {0.18f, 0.18f, 0.19f}, 0.7f, 0.2f));
  const int pavement = b.add_material(matte("pavement", {0.35f, 0.34f, 0.33f}, 0.8f, 0.15f));
  const int metal = b.add_material(matte("metal_dark", {0.15f, 0.15f, 0.16f}, 0.4f, 0.5f));
  const int lamp_glow = b.add_material(emitter("lamp_glow", {0.9f, 0.9f, 0.9f}, {1.0f, 0.9f, 0.7f}));
  const int facade[4] = {
      b.add_material(matte("facade_brown", {0.30f, 0.26f, 0.22f}, 0.85f, 0.1f)),
      b.add_material(matte("facade_slate", {0.22f, 0.24f, 0.28f}, 0.85f, 0.1f)),
      b.add_material(matte("facade_sand", {0.40f, 0.35f, 0.28f}, 0.85f, 0.1f)),
      b.add_material(matte("facade_grey", {0.27f, 0.27f, 0.27f}, 0.85f, 0.1f)),
  };
  const int glass_dark = b.add_material(matte("glass_dark", {0.02f, 0.02f, 0.025f}, 0.15f, 0.5f));
  const int window_mats[3] = {
      b.add_material(emitter("window_warm", {0.1f, 0.1f, 0.1f}, {1.0f, 0.78f, 0.45f})),
      b.add_material(emitter("window_cool", {0.1f, 0.1f, 0.1f}, {0.65f, 0.8f, 1.0f})),
      b.add_material(emitter("window_white", {0.1f, 0.1f, 0.1f}, {1.0f, 0.95f, 0.85f})),
  };

  RectMeshes rects(b);
  // Facade to facade; the buildings stand in rows without gaps.
  rects.node("ground", {0, 0, 0}, kUp, {1, 0, 0}, 16.0f, 130.0f, asphalt);
  const int sidewalk = b.add_mesh("sidewalk", make_box({3.0f, 0.15f, 124.0f}), pavement);
  b.add_mesh_node("sidewalk_l", sidewalk, {-6.5f, 0.075f, 0.0f});
  b.add_mesh_node("sidewalk_r", sidewalk, {6.5f, 0.075f, 0.0f});

  Mesh pole = make_cylinder(0.07f, 6.0f, 12);
  pole.append(make_box({arm + 0.07f, 0.08f, 0.08f}), place({(arm + 0.07f) / 2.0f, 5.9f, 0.0f}));
  const int pole_mesh = b.add_mesh("lamp_pole", pole, metal);
  const int head_mesh = b.add_mesh("lamp_head", make_box({0.5f, 0.12f, 0.3f}), lamp_glow);
  for (int side = 0; side < 2; ++side) {
    const float sign = side == 0 ? -1.0f : 1.0f;
    const std::string s = side == 0 ? "l" : "r";
    const auto rot = side == 0 ? std::nullopt : std::optional<glm::quat>(glm::angleAxis(kPi, kUp));
    for (int k = 0; k < 6; ++k) {
      const float z = lamp_z[k] + (side == 0 ? 0.0f : 10.0f) - 5.0f;
      b.add_mesh_node("pole_" + s + std::to_string(k), pole_mesh, {sign * pole_x, 0.0f, z}, rot);
      b.add_mesh_node("lamp_" + s + std::to_string(k), head_mesh, {sign * (pole_x - arm), 5.86f, z});
    }
  }

  // Buildings along both sides, facades at |x| = 8, with window grids on the street side.
  Mesh windows[4];  // warm, cool, white, dark
  const Mesh pane = make_rect(1.2f, 1.5f);
  for (int side = 0; side < 2; ++side) {
    const float sign = side == 0 ? -1.0f : 1.0f;
    const glm::vec3 n(-sign, 0.0f, 0.0f);                  // facade normal, towards the street
    const glm::vec3 right(0.0f, 0.0f, side == 0 ? -1.0f : 1.0f);  // "right" seen from the street
    float z = -60.0f;
    for (int k = 0; z < 58.0f; ++k) {
      const float w = std::min(rng.range(6.0f, 12.0f), 60.0f - z);
      const float depth = rng.range(8.0f, 14.0f), h = rng.range(6.0f, 30.0f);
      const int look = static_cast<int>(rng.below(4));
      const glm::vec3 size(depth, h, w);
      const std::string name = "building_" + std::string(side == 0 ? "l" : "r") + padded(k, 2);
      const int mesh = b.add_mesh(name, make_box(size, 0.25f), facade[look]);
      const float zc = z + w / 2.0f;
      b.add_mesh_node(name, mesh, {sign * (8.0f + depth / 2.0f), h / 2.0f, zc});
      const int cols = std::max(1, static_cast<int>((w - 1.0f) / 2.5f));
      const int rows = static_cast<int>((h - 1.0f) / 3.2f);
      for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
          const float wz = zc + (static_cast<float>(c) - 0.5f * static_cast<float>(cols - 1)) * 2.5f;
          const float wy = 1.75f + 3.2f * static_cast<float>(r);
          const float lit = rng.uniform(), kind = rng.uniform();
          const int slot = lit < 0.45f ? (kind < 0.55f ? 0 : kind < 0.8f ? 1 : 2) : 3;
          windows[slot].append(pane, place({sign * 8.0f + n.x * 0.03f, wy, wz}, face_frame(n, right)));
        }
      z += w;
    }
  }
  const char* window_names[4] = {"windows_warm", "windows_cool", "windows_white", "windows_dark"};
  for (int i = 0; i < 4; ++i)
    b.add_mesh_node(window_names[i], b.add_mesh(window_names[i], windows[i], i < 3 ? window_mats[i] : glass_dark),
                    glm::vec3(0.0f));
}
}  // namespace

void write_street(const fs::path& out) {
  const fs::path dir = fresh_dir(out, "street");
  GltfBuilder b("street");
  build_street(b, nullptr);
  b.write(dir);
}

// ---------------------------------------------------------------------------------------------
// cornell: the classic box (555 units) scaled to 2 m, every surface an analytic rect.
void write_cornell(const fs::path& out) {
  const fs::path dir = fresh_dir(out, "cornell");
  GltfBuilder b("cornell");
  b.set_ambient({0.03f, 0.03f, 0.03f});

  // The original camera: 39.3 degrees vertical field of view, centred on the opening.
  b.add_camera("front", {0.0f, 1.0f, 3.9f}, {0.0f, 1.0f, 0.0f}, 0.6864f, 0.05f, 20.0f);
  b.add_point_light("ceiling_light", {0.0f, 1.55f, 0.3f}, {1.0f, 0.93f, 0.8f}, 1.0f);

  const int white = b.add_material(matte("white", {0.73f, 0.73f, 0.73f}, 0.9f, 0.04f));
  const int red = b.add_material(matte("red", {0.63f, 0.065f, 0.05f}, 0.9f, 0.04f));
  const int green = b.add_material(matte("green", {0.14f, 0.45f, 0.091f}, 0.9f, 0.04f));
  const int patch = b.add_material(emitter("light_patch", {0.78f, 0.78f, 0.78f}, {1.0f, 0.93f, 0.8f}));

  RectMeshes rects(b);
  rects.node("floor", {0, 0, 0}, kUp, {1, 0, 0}, 2.0f, 2.0f, white);
  rects.node("ceiling", {0, 2, 0}, {0, -1, 0}, {1, 0, 0}, 2.0f, 2.0f, white);
  rects.node("back_wall", {0, 1, -1}, {0, 0, 1}, {1, 0, 0}, 2.0f, 2.0f, white);
  rects.node("left_wall", {-1, 1, 0}, {1, 0, 0}, {0, 0, -1}, 2.0f, 2.0f, red);
  rects.node("right_wall", {1, 1, 0}, {-1, 0, 0}, {0, 0, 1}, 2.0f, 2.0f, green);
  rects.node("light_patch", {0.0f, 1.998f, 0.3f}, {0, -1, 0}, {1, 0, 0}, 0.5f, 0.4f, patch);

  // The two blocks as five rects each (the bottom touches the floor and is never seen).
  auto block = [&](const std::string& prefix, glm::vec3 base_centre, glm::vec3 size, float angle) {
    const glm::mat3 r = yaw(angle);
    const glm::vec3 c = base_centre + glm::vec3(0.0f, size.y / 2.0f, 0.0f);
    const struct {
      const char* suffix;
      glm::vec3 n, x;
      float sx, sz, offset;
    } faces[5] = {
        {"_px", {1, 0, 0}, {0, 0, -1}, size.z, size.y, size.x / 2},
        {"_nx", {-1, 0, 0}, {0, 0, 1}, size.z, size.y, size.x / 2},
        {"_pz", {0, 0, 1}, {1, 0, 0}, size.x, size.y, size.z / 2},
        {"_nz", {0, 0, -1}, {-1, 0, 0}, size.x, size.y, size.z / 2},
        {"_top", {0, 1, 0}, {1, 0, 0}, size.x, size.z, size.y / 2},
    };
    for (const auto& f : faces)
      rects.node(prefix + f.suffix, c + r * (f.n * f.offset), r * f.n, r * f.x, f.sx, f.sz, white);
  };
  block("tall_box", {-0.42f, 0.0f, -0.4f}, {0.6f, 1.2f, 0.6f}, 17.0f * kPi / 180.0f);
  block("short_box", {0.35f, 0.0f, 0.32f}, {0.6f, 0.6f, 0.6f}, -17.0f * kPi / 180.0f);
  b.write(dir);
}

// ---------------------------------------------------------------------------------------------
// neon: chapter 04. Three neon tubes (node extras, see chapters/04_neon/neon_scene.h) over a
// glossy floor, one in front of a wall parallel to it (reflection rays along the tube), one
// leaning with its lower end touching the floor, one on the wall without caps and with barn
// doors; a glossy sphere; a dim moon so the scene has an ordinary light too.
void write_neon(const fs::path& out) {
  const fs::path dir = fresh_dir(out, "neon");
  GltfBuilder b("neon");
  b.set_ambient({0.02f, 0.02f, 0.025f});

  b.add_camera("overview", {0.2f, 1.7f, 4.2f}, {0.3f, 0.75f, -1.2f}, 0.75f, 0.05f, 50.0f);
  b.add_camera("grazing", {-4.6f, 1.05f, -1.35f}, {3.0f, 1.0f, -1.9f}, 0.6f, 0.05f, 50.0f);
  b.add_camera("close", {0.7f, 0.75f, 1.1f}, {1.55f, 0.1f, -0.75f}, 0.7f, 0.05f, 50.0f);

  b.add_directional_light("moon", {0.3f, -1.0f, -0.5f}, {0.55f, 0.65f, 1.0f}, 0.04f);

  // A neon node: the tube along the node's local X, the first barn door along local +Y.
  auto neon = [&](const std::string& name, glm::vec3 centre, glm::vec3 along, glm::vec3 up, json tube) {
    add_neon(b, name, centre, along, up, std::move(tube));
  };
  neon("neon_pink", {-0.7f, 1.15f, -1.7f}, {1, 0, 0}, kUp,
       {{"length", fnum(2.4f)}, {"radius", fnum(0.03f)}, {"color", jvec(glm::vec3(1.0f, 0.2f, 0.55f))},
        {"intensity", fnum(1.0f)}, {"specular", fnum(1.0f)}, {"caps", true}});
  const glm::vec3 low(1.75f, 0.03f, -0.35f), high(2.25f, 1.45f, -0.95f);  // the low end touches the floor
  neon("neon_cyan", 0.5f * (low + high), high - low, {0, 0, 1},
       {{"length", fnum(glm::length(high - low))}, {"radius", fnum(0.03f)}, {"color", jvec(glm::vec3(0.2f, 0.8f, 1.0f))},
        {"intensity", fnum(0.8f)}, {"specular", fnum(1.0f)}, {"caps", true}});
  neon("neon_amber", {2.6f, 2.3f, -1.82f}, {1, 0, 0}, kUp,
       {{"length", fnum(1.2f)}, {"radius", fnum(0.025f)}, {"color", jvec(glm::vec3(1.0f, 0.55f, 0.15f))},
        {"intensity", fnum(0.6f)}, {"specular", fnum(1.0f)}, {"caps", false},
        {"barn_doors", json::array({fnum(0.0f), fnum(2.0f), fnum(0.35f), fnum(0.5f)})}});

  const int floor_mat = b.add_material(matte("floor_glossy", {0.30f, 0.30f, 0.32f}, 0.3f, 0.5f));
  const int wall_mat = b.add_material(matte("wall_satin", {0.55f, 0.52f, 0.48f}, 0.5f, 0.25f));
  const int sphere_mat = b.add_material(matte("sphere_glossy", {0.12f, 0.12f, 0.15f}, 0.2f, 0.6f));
  RectMeshes rects(b);
  rects.node("floor", {0.0f, 0.0f, 0.0f}, kUp, {1, 0, 0}, 10.0f, 8.0f, floor_mat);
  rects.node("wall", {0.0f, 1.5f, -2.0f}, {0, 0, 1}, {1, 0, 0}, 10.0f, 3.0f, wall_mat);
  const float radius = 0.45f;
  b.add_sphere_node("sphere", b.add_mesh("sphere", make_uv_sphere(radius, 64, 32), sphere_mat), {0.6f, radius, -0.6f}, radius);
  b.write(dir);
}

// ---------------------------------------------------------------------------------------------
// street_neon: chapter 04. The night street exactly as write_street makes it (the same RNG
// draws, so the same lamps, buildings and windows), with neon signs on the building fronts:
// the facades stand at |x| = 8 without gaps from z = -60 to 58, so a sign 12 cm in front of
// one is always on a wall. Heights between the first and second rows of windows (their panes
// span y 1.0-2.5 and 4.2-5.7). Intensities give capsules of 11-16 m (one 8-bit step): from
// the pavement a view stands inside some and outside others.
namespace {
// The neon street's cameras, added before the street's own.
void add_sign_cameras(GltfBuilder& c) {
  c.add_camera("neon_signs", {0.5f, 1.8f, 52.0f}, {-0.5f, 2.7f, 26.0f}, 0.9f, 0.05f, 200.0f);
  c.add_camera("inside_sign", {-5.4f, 1.75f, 42.5f}, {-7.6f, 3.0f, 36.5f}, 0.9f, 0.05f, 200.0f);
  c.add_camera("above_signs", {1.5f, 34.0f, 64.0f}, {-0.5f, 0.0f, 19.0f}, 0.9f, 0.5f, 300.0f);
}

// The six signs on the facades.
void add_signs(GltfBuilder& b) {
  const float left = -7.88f, right = 7.88f;  // 12 cm in front of the facades
  const glm::vec3 along_street(0, 0, 1);
  auto tube = [](float length, float radius, glm::vec3 color, float intensity, bool caps) {
    return json{{"length", fnum(length)}, {"radius", fnum(radius)}, {"color", jvec(color)},
                {"intensity", fnum(intensity)}, {"specular", fnum(1.0f)}, {"caps", caps}};
  };
  add_neon(b, "sign_pink", {left, 3.35f, 38.0f}, along_street, kUp, tube(2.4f, 0.025f, {1.0f, 0.15f, 0.55f}, 1.0f, true));
  add_neon(b, "sign_cyan", {right, 3.2f, 32.0f}, kUp, {1, 0, 0}, tube(1.4f, 0.025f, {0.2f, 0.8f, 1.0f}, 0.6f, true));
  // Barn doors above and below (the first door along +Y): the light reaches the street and
  // the wall beside the tube, not the wall above and the pavement right under it.
  json green = tube(1.6f, 0.025f, {0.3f, 1.0f, 0.35f}, 0.7f, true);
  green["barn_doors"] = json::array({fnum(0.0f), fnum(2.0f), fnum(0.35f), fnum(0.5f)});
  add_neon(b, "sign_green", {left, 3.35f, 26.0f}, along_street, kUp, green);
  // One door above (a hood): the light goes down and out, not up the wall.
  json amber = tube(2.0f, 0.025f, {1.0f, 0.55f, 0.12f}, 0.8f, false);
  amber["barn_doors"] = json::array({fnum(0.1f), fnum(1.0f), fnum(0.35f), fnum(0.6f)});
  add_neon(b, "sign_amber", {right, 3.35f, 16.0f}, along_street, kUp, amber);
  add_neon(b, "sign_violet", {left, 3.3f, 10.75f}, {0.0f, 1.2f, 1.5f}, {1, 0, 0}, tube(1.9f, 0.025f, {0.6f, 0.3f, 1.0f}, 0.5f, true));
  add_neon(b, "sign_red", {right, 3.35f, -5.0f}, along_street, kUp, tube(3.0f, 0.03f, {1.0f, 0.1f, 0.08f}, 1.0f, true));
}
}  // namespace

void write_street_neon(const fs::path& out) {
  const fs::path dir = fresh_dir(out, "street_neon");
  GltfBuilder b("street_neon");
  build_street(b, add_sign_cameras);
  add_signs(b);
  b.write(dir);
}

// ---------------------------------------------------------------------------------------------
// street_shop: chapter 10's whole frame. The neon street exactly as write_street_neon makes it,
// with two shop windows on the pavements: glass display cases (alphaMode BLEND, each pane one
// face towards the street and the sky) standing out 0.9 m from a facade, a lamp inside each,
// and glass bottles on a plinth and a shelf. The cases stand in front of the facades' first
// row of windows (y 1.0-2.5), so a lit window glows through two layers of glass.
void write_street_shop(const fs::path& out) {
  const fs::path dir = fresh_dir(out, "street_shop");
  GltfBuilder b("street_shop");
  build_street(b, [](GltfBuilder& c) {
    c.add_camera("shops", {1.0f, 2.2f, 50.0f}, {0.0f, 1.6f, 30.0f}, 0.9f, 0.05f, 200.0f);
    c.add_camera("shop_window", {-4.6f, 1.65f, 37.2f}, {-7.5f, 1.2f, 32.0f}, 0.9f, 0.05f, 200.0f);
    add_sign_cameras(c);
  });
  add_signs(b);

  auto glass = [&](const char* name, glm::vec3 color, float alpha) { return b.add_material(glass_material(name, color, alpha, 0.1f)); };
  const int pane = glass("shop_glass", {0.85f, 0.95f, 0.95f}, 0.15f);
  const int bottle_mats[3] = {glass("bottle_green", {0.15f, 0.6f, 0.2f}, 0.55f),
                              glass("bottle_amber", {0.85f, 0.45f, 0.08f}, 0.6f),
                              glass("bottle_clear", {0.8f, 0.9f, 0.95f}, 0.3f)};
  const int wood = b.add_material(matte("shop_wood", {0.35f, 0.2f, 0.1f}, 0.6f, 0.2f));

  Mesh bottle = make_cylinder(0.07f, 0.26f, 16);
  bottle.append(make_uv_sphere(0.07f, 16, 8), place({0.0f, 0.26f, 0.0f}));
  bottle.append(make_cylinder(0.025f, 0.12f, 10), place({0.0f, 0.31f, 0.0f}));
  int bottle_mesh[3];
  for (int i = 0; i < 3; ++i) bottle_mesh[i] = b.add_mesh(std::string("bottle_") + std::to_string(i), bottle, bottle_mats[i]);

  RectMeshes rects(b);
  // side: -1 the left facade (x = -8), +1 the right (x = +8); the case spans z0 .. z0 + length.
  auto shop = [&](const std::string& name, float side, float z0, float length, glm::vec3 lamp) {
    const float depth = 0.9f, y0 = 0.15f, y1 = 2.6f;  // on the pavement (top at 0.15 m)
    const float face = side * (8.0f - depth), mid = side * (8.0f - depth / 2.0f), zc = z0 + length / 2.0f;
    const glm::vec3 out_n(-side, 0, 0), along(0, 0, side);  // towards the street; "right" seen from it
    rects.node(name + "_front", {face, (y0 + y1) / 2.0f, zc}, out_n, along, length, y1 - y0, pane);
    rects.node(name + "_top", {mid, y1, zc}, kUp, {1, 0, 0}, depth, length, pane);
    rects.node(name + "_end_a", {mid, (y0 + y1) / 2.0f, z0}, {0, 0, -1}, {-1, 0, 0}, depth, y1 - y0, pane);
    rects.node(name + "_end_b", {mid, (y0 + y1) / 2.0f, z0 + length}, {0, 0, 1}, {1, 0, 0}, depth, y1 - y0, pane);
    // The plinth stops 5 cm behind the front pane (a shared plane would z-fight with the glass).
    b.add_mesh_node(name + "_plinth", b.add_mesh(name + "_plinth", make_box({depth - 0.05f, 0.4f, length - 0.1f}), wood),
                    {side * (8.0f - (depth - 0.05f) / 2.0f), y0 + 0.2f, zc});
    b.add_mesh_node(name + "_shelf", b.add_mesh(name + "_shelf", make_box({depth * 0.6f, 0.04f, length}), wood),
                    {side * (8.0f - depth * 0.3f), 1.3f, zc});
    const int per_row = static_cast<int>(length / 0.45f);
    for (int row = 0; row < 2; ++row)
      for (int i = 0; i < per_row; ++i) {
        const float z = z0 + (static_cast<float>(i) + 0.5f) * length / static_cast<float>(per_row);
        const float y = row == 0 ? y0 + 0.4f : 1.32f, x = side * (8.0f - (row == 0 ? 0.55f : 0.3f));
        b.add_mesh_node(name + "_bottle_" + std::to_string(row) + padded(i, 2), bottle_mesh[(i + row) % 3], {x, y, z});
      }
    b.add_point_light(name + "_lamp", lamp, {1.0f, 0.8f, 0.55f}, 0.35f, std::sqrt(0.35f / 0.015f));
  };
  shop("shop_l", -1.0f, 30.0f, 4.0f, {-7.55f, 2.35f, 32.0f});
  shop("shop_r", 1.0f, 38.5f, 3.5f, {7.55f, 2.35f, 40.25f});
  b.write(dir);
}

}  // namespace scenegen

namespace scenegen {

// ---------------------------------------------------------------------------------------------
// glass: chapter 10's transparency. Thin panes of tinted glass (alphaMode BLEND, one face each:
// back faces are culled, so a pane is one layer) standing one behind another in front of a lit
// wall, a floor and an opaque box; two panes cross in an X (where sorting whole panes cannot be
// right), and one pane stands behind the wall (the depth test must hide it).
void write_glass(const fs::path& out) {
  const fs::path dir = fresh_dir(out, "glass");
  GltfBuilder b("glass");
  b.set_ambient({0.04f, 0.04f, 0.045f});

  b.add_camera("front", {0.0f, 1.4f, 5.5f}, {0.0f, 0.9f, -0.5f}, 0.75f, 0.05f, 100.0f);
  b.add_camera("side", {3.6f, 1.6f, 4.2f}, {0.2f, 0.9f, -0.6f}, 0.75f, 0.05f, 100.0f);
  b.add_camera("crossing", {1.6f, 1.6f, 2.8f}, {2.0f, 0.9f, -0.4f}, 0.7f, 0.05f, 100.0f);

  b.add_directional_light("sun", {0.35f, -0.75f, -0.55f}, {1.0f, 0.9f, 0.75f}, 0.6f);
  b.add_point_light("lamp_warm", {-2.2f, 2.4f, 1.5f}, {1.0f, 0.7f, 0.4f}, 4.0f, 12.0f);
  b.add_point_light("lamp_cool", {2.4f, 2.0f, 2.0f}, {0.5f, 0.7f, 1.0f}, 3.0f, 12.0f);

  RectMeshes rects(b);
  const int floor_mat = b.add_material(matte("floor", {0.35f, 0.35f, 0.33f}, 0.8f, 0.2f));
  const int wall_mat = b.add_material(matte("wall", {0.5f, 0.48f, 0.45f}, 0.7f, 0.2f));
  const int box_mat = b.add_material(matte("box_red", {0.7f, 0.15f, 0.1f}, 0.4f, 0.4f));
  rects.node("floor", {0.0f, 0.0f, 0.0f}, kUp, {1, 0, 0}, 10.0f, 10.0f, floor_mat);
  rects.node("wall", {0.0f, 2.0f, -3.0f}, {0, 0, 1}, {1, 0, 0}, 10.0f, 4.0f, wall_mat);
  b.add_mesh_node("box", b.add_mesh("box", make_box({0.8f, 0.8f, 0.8f}), box_mat), {-0.4f, 0.4f, -1.9f});

  auto glass = [&](const char* name, glm::vec3 color, float alpha) { return b.add_material(glass_material(name, color, alpha, 0.15f)); };
  const int blue = glass("glass_blue", {0.15f, 0.35f, 0.9f}, 0.35f);
  const int amber = glass("glass_amber", {0.95f, 0.6f, 0.1f}, 0.5f);
  const int green = glass("glass_green", {0.2f, 0.8f, 0.3f}, 0.6f);
  const int pink = glass("glass_pink", {0.95f, 0.3f, 0.6f}, 0.25f);
  const int clear = glass("glass_clear", {0.9f, 0.95f, 1.0f}, 0.2f);
  const int violet = glass("glass_violet", {0.55f, 0.25f, 0.9f}, 0.45f);
  const int hidden = glass("glass_hidden", {0.1f, 1.0f, 0.9f}, 0.8f);

  // Four panes one behind another (0.6 m apart), shifted so that 1 to 4 overlap on screen.
  const glm::vec3 facing(0, 0, 1), right(1, 0, 0);
  rects.node("pane_blue", {-1.1f, 0.9f, 0.8f}, facing, right, 1.4f, 1.6f, blue);
  rects.node("pane_amber", {-0.5f, 1.1f, 0.2f}, facing, right, 1.4f, 1.6f, amber);
  rects.node("pane_green", {0.1f, 0.9f, -0.4f}, facing, right, 1.4f, 1.6f, green);
  rects.node("pane_pink", {-0.6f, 1.5f, -1.0f}, facing, right, 1.8f, 1.2f, pink);
  // Two panes crossing in an X: each is in front of the other on one side of the crossing line.
  const float a = 0.6f;
  rects.node("cross_clear", {2.0f, 0.9f, -0.4f}, {std::sin(a), 0.0f, std::cos(a)}, {std::cos(a), 0.0f, -std::sin(a)},
             1.4f, 1.6f, clear);
  rects.node("cross_violet", {2.0f, 0.9f, -0.4f}, {-std::sin(a), 0.0f, std::cos(a)}, {std::cos(a), 0.0f, std::sin(a)},
             1.4f, 1.6f, violet);
  // Behind the wall: never seen.
  rects.node("pane_hidden", {0.0f, 1.2f, -3.5f}, facing, right, 2.0f, 1.6f, hidden);
  b.write(dir);
}

}  // namespace scenegen
