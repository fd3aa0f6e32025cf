#pragma once
// Chapter 08's ground truth: one-bounce diffuse indirect light ray traced on the CPU
// (common/raytrace.h), of the same direct light the frame computes. With the book's display
// units (chapter 01: the Lambert 1/pi folded into the lights), the light buffer's L1 is the
// irradiance over pi, and the indirect part of it at a point p with normal n is
//   L1_ind(p) = (1 / pi) * integral over the hemisphere of L(p, w) (n . w) dw,
// L(p, w) the radiance arriving from w: the albedo x L1_direct of the surface the ray from p
// toward w meets first (nothing from the sky). Estimated with `samples` cosine-weighted rays
// (pdf (n . w) / pi, so the estimate is the plain mean of L over the rays) about the GEOMETRIC
// normal of the triangle the pixel sees (chapter 07's reason: no ray starts below its own
// surface), unbounded in length. At each hit: chapter 03's light set with chapter 01's model and
// chapter 03's light cut (gi_math.h's direct_diffuse), at the hit's shading normal turned to the
// side the ray came from, times the hit's albedo (its texture too). No volume, no stencil, no
// screen: every surface the ray meets counts, on screen or not, front or back.
//
// What the indirect pass reads, the truth reads: the direct diffuse light, not the emitted light
// (emissive surfaces send no indirect light in either: the Cornell box's light patch stands for
// its point light, whose light is already counted) and not the ambient light (it is a constant
// stand-in for all the light not modelled, itself indirect; it is not bounced again).
#include <cstdint>

#include "chapters/03_light_volumes/light_instances.h"
#include "common/camera.h"
#include "common/image.h"
#include "common/scene.h"

namespace lp {
class RayScene;
}

namespace lp::ch08 {

struct GiTruthSettings {
  int samples = 256;            // rays per pixel
  int bounces = 1;              // 1, or 2: each hit sends one more cosine-weighted ray (the second bounce)
  bool shadows = false;         // trace the direct light's shadows (the frame has a shadow stage); the
                                // Cornell box's frame has none: its point light reaches every surface facing it
  // Screen-limited: count only the hits the indirect pass can know, within `screen_radius` of
  // the point and seen by the camera (inside the image, not hidden). The full truth minus this is
  // what any screen-space method must miss.
  bool screen_limited = false;
  float screen_radius = 2.5f;
  std::uint64_t seed = 0x4749u;
};

inline constexpr float kTruthSky = -1.f;  // every channel, where no surface is seen

// [truth]
// The truth image: rgb L1_ind (before the receiver's albedo), rows top to bottom, kTruthSky on the sky.
ImageF ray_traced_indirect(const Scene& scene, const RayScene& rays, const ch03::LightSet& lights,
                           const FrameCamera& camera, int width, int height, const GiTruthSettings& s);
// The same through the on-disk cache (common/raytrace.h's cached_image); the light set is in the key.
ImageF cached_ray_traced_indirect(const Scene& scene, const ch03::LightSet& lights, const FrameCamera& camera,
                                  int width, int height, const GiTruthSettings& s);
// [/truth]

// [errors]
// An estimate of L1_ind (3 or 4 channels, rgb used) against the truth over the pixels both
// see geometry in, optionally only inside `mask` (1 = counted, top row first).
struct GiErrors {
  double mean_abs = 0;        // mean over pixels and channels of |estimate - truth|
  double relative = 0;        // mean_abs / mean truth
  double captured = 0;        // sum estimate / sum truth: the fraction of the true energy found
  double mean_truth = 0, mean_estimate = 0;
  long pixels = 0;
};
GiErrors gi_errors(const ImageF& estimate, const ImageF& truth, const std::vector<std::uint8_t>* mask = nullptr);
// Per pixel mean |estimate - truth| over rgb (0 on the sky), for the heat map.
ImageF gi_error_map(const ImageF& estimate, const ImageF& truth);
// [/errors]

}  // namespace lp::ch08
