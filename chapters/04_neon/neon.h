#pragma once
// The neon (line) light on the CPU: the geometry of closest points, the ground truth
// (numerical integration along the tube) and every approximation the chapter compares.
// shaders/neon.glsl is the same maths in GLSL; the unit tests hold this file to the
// formulas and to the ground truth, and a GPU test holds the GLSL to this file.
//
// Units are those of chapter 01: a point light of intensity I gives irradiance
// I cos(theta) / d^2, and the reflected light is albedo x diffuse + specular colour x specular.
// A tube of length L and intensity I is a continuum of point lights, I / L per metre.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "chapters/03_light_volumes/light_radius.h"

namespace lp::ch04 {

// [neon-light]
// The thesis's "barn doors": flaps around the tube that shade part of its light.
struct BarnDoors {
  float distance = 0;       // the mask acts only farther than this from the tube
  float count = 0;          // doors evenly spaced around the axis (0: none)
  float transmittance = 1;  // 0..1: how much light a door lets through
  float softness = 1;       // larger: softer edges, and they soften with distance
  bool enabled() const { return count > 0; }
};

// One neon tube, as a scene describes it (node extras, see neon_scene.h).
struct NeonLight {
  std::string name;
  glm::vec3 start{0}, end{1, 0, 0};  // world space: the ends of the tube's axis
  glm::vec3 door_axis{0, 1, 0};      // unit, perpendicular to the axis: the first door's side
  float radius = 0.02f;              // the glass tube: no surface is closer to the axis
  glm::vec3 color{1};
  float intensity = 1;   // the whole tube; each metre emits intensity / length
  float specular = 1;    // scales the specular term only (1: physical)
  bool caps = true;      // false: the volume is a cylinder and nothing beyond the ends is lit
  BarnDoors barn_doors;
  float length() const { return glm::length(end - start); }
};
// [/neon-light]

// What the shading needs to know of a surface point (as chapter 01's SurfacePoint, without
// the material colours: the methods return light, which the caller multiplies by them).
struct NeonSurface {
  glm::vec3 position{0};
  glm::vec3 normal{0, 1, 0};  // unit
  glm::vec3 to_eye{0, 1, 0};  // unit, towards the camera
  float exponent = 32;        // Blinn-Phong exponent (chapter 01's exponent_from_roughness)
};

// Light arriving and reflected, before the albedo and the specular colour.
struct NeonResult {
  glm::vec3 diffuse{0}, specular{0};
};

// The methods of the chapter, in the order of the program's modes.
enum class Method { GroundTruth, Source, Improved, Points, RepresentativePoint, AnalyticDiffuse };
inline const std::vector<std::string> kMethodNames = {"ground-truth", "source", "improved", "points",
                                                      "representative-point", "analytic-diffuse"};
Method method_from_name(const std::string& name);  // throws Error for an unknown name

// --- Geometry ------------------------------------------------------------------------------

// Parameter t in [0, 1] of the point of segment [a, b] closest to p (0 for a zero-length one).
float closest_on_segment(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b);

struct SegmentRayClosest {
  float s = 0;  // on the segment: a + s (b - a), s in [0, 1]
  float t = 0;  // on the ray: origin + t dir, t >= 0
  glm::vec3 on_segment{0}, on_ray{0};
  float distance = 0;
  bool parallel = false;  // the two directions are parallel (the closest pair is not unique)
};
// Closest points between segment [a, b] and the ray origin + t dir (t >= 0, dir unit).
// Always a true closest pair, never NaN: zero-length segments, parallel and nearly
// parallel directions and rays starting on the segment included.
SegmentRayClosest closest_segment_ray(const glm::vec3& a, const glm::vec3& b, const glm::vec3& origin,
                                      const glm::vec3& dir);

// The tube seen from a shading point x: P(s) - x = d w + s u, with the ends at s0 <= s1.
struct LineFrame {
  glm::vec3 u{1, 0, 0};  // unit axis, start -> end
  glm::vec3 w{0, 1, 0};  // unit, from x perpendicular to the axis line
  float d = 0;           // distance from x to the axis line, at least the tube radius
  float s0 = 0, s1 = 0;  // the ends, measured along u from the foot of the perpendicular
};
LineFrame line_frame(const glm::vec3& x, const NeonLight& light, const glm::vec3& normal);
// Keeps only the part of the tube above the surface's tangent plane; false when none is.
bool clip_to_horizon(const LineFrame& f, const glm::vec3& normal, float& s0, float& s1);

// --- Extent --------------------------------------------------------------------------------

// An upper bound of the irradiance the tube gives any surface at distance r from it: the
// integral of (I max(colour) / L) / r^2 along the tube as if every piece of it were seen
// head-on, largest beside the middle: (I max(colour) / L) (2 / r) atan(L / 2r). (A real
// surface sees the pieces at an angle and gets between 2/pi and all of it.) The volume
// radius is where the bound falls to `threshold`.
float max_irradiance_at(const NeonLight& light, float r);
// [neon-cut]
// Where a tube's volume ends. Chapter 03 cuts a light where it falls to one sRGB step at black
// for the scene's brightest material (light_radius.h), and its lamps fade to zero at their
// glTF range anyway. A tube has no range: its light falls as 1/r^2 for ever, and that rule
// would end our tubes' volumes 430-900 m away (peak reflectance 94 in the room, 247 on the
// street's glass), beyond every view: no volume at all. So a tube is cut where its light falls
// to one sRGB step at black for a white matte surface, chapter 03's step without the peak:
// 40-57 m for the scenes' tubes. (The source's linear 1/256 cut at 12-16 m, where a white
// surface drops by 12.7 steps to black.) Beyond the cut a surface loses at most one step,
// times what it reflects beyond a white matte one; the tests bound what is lost.
inline constexpr float kNeonCut = ch03::kSrgbFirstStep;
// [/neon-cut]
float volume_radius(const NeonLight& light, float threshold = kNeonCut);
// The barn doors' edges soften with the distance relative to the thesis's light radius R. Ours
// is fixed where the tube's light falls to 1/256 (the source's cut), so the doors keep their
// shape wherever the volume ends.
inline constexpr float kDoorsReach = 1.f / 256.f;
inline float doors_radius(const NeonLight& light) { return volume_radius(light, kDoorsReach); }
// 1 inside the light's volume (capsule, or cylinder without caps), 0 outside.
float volume_mask(const glm::vec3& x, const NeonLight& light, float volume_radius);
// The barn-doors factor in [0, 1] (1 where there are no doors), doors_radius() scaling its softness.
float barn_doors_mask(const glm::vec3& x, const NeonLight& light, float doors_radius);

// --- The methods, for a tube of unit intensity and white colour -----------------------------
// Each returns (diffuse, specular) light for I = 1; neon_light() scales by colour x intensity.
struct Terms {
  float diffuse = 0, specular = 0;
};
Terms ground_truth_terms(const NeonSurface& s, const NeonLight& light, int samples);
Terms analytic_diffuse_terms(const NeonSurface& s, const NeonLight& light);  // specular 0
Terms improved_terms(const NeonSurface& s, const NeonLight& light);
Terms points_terms(const NeonSurface& s, const NeonLight& light, int count);
Terms representative_point_terms(const NeonSurface& s, const NeonLight& light);
// The thesis's light is k (1 - d/R)^2 in front of the tube: an artist's window, not a
// physical falloff. fit_source() picks its R and k (per unit intensity) to meet the truth at
// L/2 and 2L in front of the tube's middle, the best chance we can give it.
struct SourceFit {
  float radius = 1, scale = 1;
};
SourceFit fit_source(float length);
Terms source_terms(const NeonSurface& s, const NeonLight& light);

// One tube's light on a surface point by `method` (samples: ground truth and points), with
// the volume and the barn doors applied, in colour. The ground truth is not cut: its volume
// has no radius (a cylinder's ends still bound it: they are part of the light). doors_radius
// < 0: doors_radius(light), computed.
NeonResult neon_light(const NeonSurface& s, const NeonLight& light, Method method, int samples, float volume_radius,
                      float doors_radius = -1);

}  // namespace lp::ch04
