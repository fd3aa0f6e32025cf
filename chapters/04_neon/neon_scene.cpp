#include "chapters/04_neon/neon_scene.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "common/error.h"

namespace lp::ch04 {

namespace {

using nlohmann::json;

float number(const json& j, const char* key, float fallback, const std::string& where) {
  if (!j.contains(key)) return fallback;
  if (!j[key].is_number()) throw Error(where + ": \"" + key + "\" must be a number");
  return j[key].get<float>();
}

}  // namespace

NeonLight parse_neon(const std::string& node, const glm::mat4& world, const std::string& lightpass_json) {
  const std::string where = "neon light '" + node + "'";
  json all = json::parse(lightpass_json, nullptr, false);
  if (all.is_discarded() || !all.is_object() || !all.contains("neon") || !all["neon"].is_object())
    throw Error(where + ": extras.lightpass.neon must be an object");
  const json& j = all["neon"];
  if (!j.contains("length")) throw Error(where + ": \"length\" is missing");
  if (!j.contains("intensity")) throw Error(where + ": \"intensity\" is missing");
  NeonLight l;
  l.name = node;
  float length = number(j, "length", 0, where);
  l.intensity = number(j, "intensity", 1, where);
  l.radius = number(j, "radius", l.radius, where);
  l.specular = number(j, "specular", l.specular, where);
  // Finite and of a size a sign can have: 1e30 m would overflow the capsule's arithmetic.
  constexpr float kLargest = 1e4f;
  if (!(length >= 0 && length <= kLargest)) throw Error(where + ": \"length\" must be >= 0 and at most 10000 (metres)");
  if (!(l.intensity > 0 && std::isfinite(l.intensity))) throw Error(where + ": \"intensity\" must be > 0 and finite");
  if (!(l.radius > 0 && l.radius <= kLargest)) throw Error(where + ": \"radius\" must be > 0 and at most 10000");
  if (!(l.specular >= 0 && std::isfinite(l.specular))) throw Error(where + ": \"specular\" must be >= 0 and finite");
  if (j.contains("color")) {
    const json& c = j["color"];
    if (!c.is_array() || c.size() != 3 || !c[0].is_number() || !c[1].is_number() || !c[2].is_number())
      throw Error(where + ": \"color\" must be [r, g, b]");
    l.color = {c[0].get<float>(), c[1].get<float>(), c[2].get<float>()};
    for (int i = 0; i < 3; ++i)
      if (!(l.color[i] >= 0 && std::isfinite(l.color[i]))) throw Error(where + ": \"color\" must be three finite numbers >= 0");
  }
  if (j.contains("caps")) {
    if (!j["caps"].is_boolean()) throw Error(where + ": \"caps\" must be true or false");
    l.caps = j["caps"].get<bool>();
  }
  if (j.contains("barn_doors")) {
    const json& b = j["barn_doors"];
    if (!b.is_array() || b.size() != 4) throw Error(where + ": \"barn_doors\" must be [distance, count, transmittance, softness]");
    for (const auto& v : b)
      if (!v.is_number()) throw Error(where + ": \"barn_doors\" must hold numbers");
    l.barn_doors = {b[0].get<float>(), b[1].get<float>(), b[2].get<float>(), b[3].get<float>()};
    for (float v : {l.barn_doors.distance, l.barn_doors.count, l.barn_doors.transmittance, l.barn_doors.softness})
      if (!std::isfinite(v)) throw Error(where + ": \"barn_doors\" must hold finite numbers");
  }
  // The tube along the node's local X, centred on its origin; the first door along local +Y.
  glm::vec3 centre(world[3]), x_axis(world[0]), y_axis(world[1]);
  if (glm::length(x_axis) == 0) throw Error(where + ": the node's X axis is degenerate (zero scale)");
  glm::vec3 along = glm::normalize(x_axis);
  l.start = centre - 0.5f * length * along;
  l.end = centre + 0.5f * length * along;
  glm::vec3 side = y_axis - glm::dot(y_axis, along) * along;
  l.door_axis = glm::dot(side, side) > 1e-12f ? glm::normalize(side) : glm::vec3(0, 1, 0);
  return l;
}

std::vector<NeonLight> neon_lights(const Scene& scene) {
  std::vector<NeonLight> out;
  for (const auto& e : scene.node_extras) {
    json j = json::parse(e.lightpass_json, nullptr, false);
    if (j.is_object() && j.contains("neon")) out.push_back(parse_neon(e.name, e.world, e.lightpass_json));
  }
  return out;
}

}  // namespace lp::ch04
