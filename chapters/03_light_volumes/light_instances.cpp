#include "chapters/03_light_volumes/light_instances.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/02_gbuffer/encoding.h"
#include "chapters/03_light_volumes/light_radius.h"

namespace lp::ch03 {

PointInstance pack_point(const Light& l, float radius) {
  return {glm::vec4(l.position, radius), glm::vec4(l.color * l.intensity, std::max(l.range, 0.f))};
}

SpotInstance pack_spot(const Light& l, float radius) {
  ch01::GpuLight g = ch01::pack_light(l);  // chapter 01's cone terms, computed once, the same way
  return {glm::vec4(l.position, radius), glm::vec4(l.color * l.intensity, std::max(l.range, 0.f)),
          glm::vec4(ch02::octahedral_fold(glm::normalize(l.direction)), g.spot.x, g.spot.y)};
}

ch01::GpuLight unpack(const PointInstance& p) {
  return {glm::vec4(glm::vec3(p.position_radius), 1.f), glm::vec4(0, 0, -1, p.radiance_range.w),
          glm::vec4(glm::vec3(p.radiance_range), 0.f), glm::vec4(0)};
}

ch01::GpuLight unpack(const SpotInstance& s) {
  return {glm::vec4(glm::vec3(s.position_radius), 2.f),
          glm::vec4(ch02::octahedral_unfold(glm::vec2(s.direction_cone)), s.radiance_range.w),
          glm::vec4(glm::vec3(s.radiance_range), 0.f), glm::vec4(s.direction_cone.z, s.direction_cone.w, 0, 0)};
}

glm::mat3 basis_around(const glm::vec3& n) {
  const float sign = n.z >= 0.f ? 1.f : -1.f;  // as the GLSL twin: -0 counts as +
  const float a = -1.f / (sign + n.z), b = n.x * n.y * a;
  return glm::mat3(glm::vec3(1.f + sign * n.x * n.x * a, sign * b, -sign * n.x), glm::vec3(b, sign + n.y * n.y * a, -n.y), n);
}

glm::mat4 volume_transform(const PointInstance& p) {
  const float r = p.position_radius.w;
  return glm::scale(glm::translate(glm::mat4(1), glm::vec3(p.position_radius)), glm::vec3(r));
}

glm::mat4 volume_transform(const SpotInstance& s, bool as_cone) {
  const float r = s.position_radius.w;
  if (!as_cone) return glm::scale(glm::translate(glm::mat4(1), glm::vec3(s.position_radius)), glm::vec3(r));
  const float c = s.direction_cone.z, tan_outer = std::sqrt(std::max(0.f, 1.f - c * c)) / c;
  const glm::mat3 m = basis_around(ch02::octahedral_unfold(glm::vec2(s.direction_cone))) *
                      glm::mat3(glm::vec3(r * tan_outer, 0, 0), glm::vec3(0, r * tan_outer, 0), glm::vec3(0, 0, r));
  glm::mat4 out(m);
  out[3] = glm::vec4(glm::vec3(s.position_radius), 1.f);
  return out;
}

namespace {

// Collects one kind of problem and says it once, with the first few names.
struct Complaint {
  std::string what;
  std::vector<std::string> names;
  void add(const std::string& name) { names.push_back(name); }
  void report(std::vector<std::string>& out) const {
    if (names.empty()) return;
    std::ostringstream s;
    s << what << ": ";
    for (std::size_t i = 0; i < std::min<std::size_t>(3, names.size()); ++i) s << (i ? ", " : "") << "'" << names[i] << "'";
    if (names.size() > 3) s << ", ...";
    s << " (" << names.size() << ")";
    out.push_back(s.str());
  }
};


}  // namespace

LightSet build_light_set(const std::vector<Light>& lights, float threshold, const VolumeShapes& shapes) {
  LightSet set;
  Complaint dark{"lights that give no light (intensity or colour 0) are left out"};
  Complaint wide{"spots of 90 degrees or more (glTF allows up to 90) are drawn with a sphere"};
  std::size_t defective = 0;
  for (const Light& l : lights) {
    // The loader's one rule (common/scene.h light_defect), for lights made in code: the same
    // light is left out, for the same reason, whichever way it came.
    if (const auto why = light_defect(l)) {
      if (++defective <= 3) set.warnings.push_back("light '" + l.name + "' is left out: " + *why);
      continue;
    }
    if (l.type == LightType::Directional) {
      set.directional.push_back(ch01::pack_light(l));
      continue;
    }
    const float radius = light_radius(l, threshold);
    if (!(radius > 0)) {
      dark.add(l.name);
      continue;
    }
    if (l.type == LightType::Point) {
      set.points.push_back(pack_point(l, radius));
    } else if (spot_uses_cone(l.outer_cone, shapes.cone_volume, shapes.sphere_volume)) {
      set.cones.push_back(pack_spot(l, radius));
    } else {
      if (!(l.outer_cone < 0.5f * std::numbers::pi_v<float>)) wide.add(l.name);
      set.wide_spots.push_back(pack_spot(l, radius));
    }
  }
  if (defective > 3) set.warnings.push_back(std::to_string(defective - 3) + " more lights are left out for the same reasons");
  for (const Complaint* c : {&dark, &wide}) c->report(set.warnings);
  return set;
}

}  // namespace lp::ch03
