#pragma once
// Chapter 08's maths on the CPU, the twin of shaders/ssgi.comp: the disk-to-disk transfer
// term that carries light from one screen sample to the pixel, the three sampling patterns of
// the 2D region around a pixel, and the direct light of chapter 03's light set (its light
// cut included) that the ray-traced truth evaluates at each hit. Unit tests hold these; the
// image tests hold the GLSL.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "chapters/01_forward/light_buffer.h"
#include "chapters/03_light_volumes/light_instances.h"

namespace lp::ch08 {

// [transfer]
// The light a small Lambertian disk (the emitter: area A, unit normal n_o, at e) sends to a
// point (the receiver: unit normal n_p, at p), as a fraction of the disk's radiance: the form
// factor from the point to the disk. For a disk of radius a seen on its axis from a distance r
// it is exact (the disk covers a cone of half-angle alpha; projected onto the receiver's base
// it covers sin^2 alpha of the unit disk):
//   F = sin^2 alpha = a^2 / (r^2 + a^2) = A / (pi r^2 + A).
// Off the axis we tilt both ends by their cosines, as the small-disk form factor
// A cos(theta_o) cos(theta_p) / (pi r^2) does, and keep the +A from the exact case:
//   F = A max(cos theta_o, 0) max(cos theta_p, 0) / (pi r^2 + A),
//   cos theta_p = n_p . v,  cos theta_o = -n_o . v,  v = (e - p) / r.
// The +A keeps F finite as r -> 0 (at most cos cos <= 1, never a division by zero). An emitter
// behind the receiver (cos theta_p <= 0) or facing away from it (cos theta_o <= 0) sends
// nothing. Reciprocity: A_p F(p <- e) = A_e F(e <- p) holds exactly when the two disks have the
// same area; otherwise the two sides differ by the ratio (pi r^2 + A_p) / (pi r^2 + A_e).
float disk_transfer(glm::vec3 receiver, glm::vec3 receiver_normal, glm::vec3 emitter, glm::vec3 emitter_normal,
                    float emitter_area);
// [/transfer]

// [patterns]
// Where the samples of the 2D region fall: point i of n, in the unit disk. Every pattern gives
// each sample the same share of the disk's area (pi / n), so a sample stands for a disk of
// area pi R^2 / n at the receiver's depth.
//   regular:    rings x spokes, the same directions at every ring and every pixel: sparse
//               spokes skip bands of surface (the source's figure 31, the banding artefact).
//   spiral:     chapter 07's golden-angle spiral, radius sqrt((i + 0.5) / n): no two samples
//               share a direction.
//   randomised: the spiral turned by an angle and shifted along its radius by two numbers
//               that change per pixel (a hash of the pixel): no pattern repeats, the error
//               becomes noise, and the bilateral blur removes most of it.
enum class Pattern { Regular, Spiral, Randomised };
inline const std::vector<std::string> kPatternNames = {"regular", "spiral", "randomised"};
glm::vec2 pattern_point(Pattern pattern, int i, int n, glm::uvec2 pixel = glm::uvec2(0));
// The regular pattern's rings for n samples: the largest r with r * r <= n (spokes = n / rings;
// the rest of n, n - rings * spokes, are not used: a regular grid has no place for them).
int regular_rings(int n);
// The per-pixel numbers of the randomised pattern, in [0, 1): the GLSL's hash, bit for bit.
glm::vec2 pixel_jitter(glm::uvec2 pixel);
// [/patterns]

// [direct-light]
// The direct diffuse light L1 (before the albedo) that chapter 03's frame gives a surface at
// `position` with unit `normal`: every light of the set, chapter 01's attenuation, and the
// cut: a local light reaches no farther than its volume's radius, as chapter 03's light shader
// tests. `shadowed(i, to_light, distance)` may say that light i (in light order: directional
// first, then points, cones, wide spots) is blocked; the truth traces it when the frame has
// shadows. Never the frame's shortcuts: no volume, no stencil, every light at every point.
struct DirectLightSet {
  std::vector<ch01::GpuLight> lights;  // directional lights, then the local ones in light order
  std::vector<float> cut;              // per light: the distance it reaches (infinity: directional)
};
DirectLightSet direct_lights(const ch03::LightSet& set);
// GLSL light_incident's twin for one packed light: direction to it and radiance there.
void incident(const ch01::GpuLight& light, glm::vec3 position, glm::vec3& to_light, glm::vec3& radiance,
              float& distance);
template <class Shadowed>
glm::vec3 direct_diffuse(const DirectLightSet& set, glm::vec3 position, glm::vec3 normal, Shadowed&& shadowed) {
  glm::vec3 sum(0);
  for (std::size_t i = 0; i < set.lights.size(); ++i) {
    glm::vec3 to_light, radiance;
    float distance;
    incident(set.lights[i], position, to_light, radiance, distance);
    if (distance > set.cut[i]) continue;
    float n_dot_l = glm::dot(normal, to_light);
    if (n_dot_l <= 0.f) continue;
    if (shadowed(int(i), to_light, distance)) continue;
    sum += radiance * n_dot_l;
  }
  return sum;
}
// [/direct-light]

}  // namespace lp::ch08
