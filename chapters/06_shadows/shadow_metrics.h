#pragma once
// Chapter 06's metrics that tell the filtered methods apart, in one place: the GL tests and the
// sweep both call these. The mean error over every sunlit pixel (shadow_truth.h's
// visibility_error) is mostly the lit and the fully shadowed pixels, where every method is
// right; it ranks where a method puts its edges, not how it filters them. These look where the
// methods differ:
//   - the penumbra error: the mean |v - reference| over the pixels where the reference lies
//     strictly between 0 and 1, widened by kPenumbraBand pixels (a method whose penumbra is
//     too narrow or too wide is wrong just outside the reference's);
//   - light leaks: pixels the soft truth has in full shadow (no ray to any of the sun's disk
//     reaches the sky) that a method lights by more than kLeakThreshold;
//   - the filtered hard truth: the hard ray-traced visibility box-filtered over a fixed
//     kernel's footprint in the light's plane, which is what a fixed PCF kernel estimates (the
//     soft truth is what a kernel as wide as the sun's penumbra would estimate).
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "chapters/06_shadows/shadow_math.h"
#include "common/camera.h"
#include "common/image.h"
#include "common/raytrace.h"
#include "common/scene.h"

namespace lp::ch06 {

// [penumbra-metric]
inline constexpr int kPenumbraBand = 2;         // pixels around the reference's penumbra (Chebyshev distance)
inline constexpr float kLeakThreshold = 0.1f;   // a fully shadowed pixel lit above this leaks

// The pixels the method's picture (show_visibility.frag) paints as sky or facing away: where
// the rasterised fragment and the truth's centre ray saw different surfaces (a silhouette),
// which is no shadow error. Blue: b > 0.3 and r < 0.2.
std::vector<bool> outside_method_mask(const ImageF& visibility);

// The reference's penumbra: pixels inside its mask (channel 2) where `channel` lies strictly
// between 0 and 1, and the masked pixels within `band` pixels of one.
std::vector<bool> penumbra_pixels(const ImageF& reference, int channel, int band = kPenumbraBand);

struct PenumbraError {
  double mean_abs = 0;     // mean |v - reference| over the penumbra
  double mean_signed = 0;  // mean v - reference: above 0 the method lights the penumbra too much
  std::size_t pixels = 0;  // pixels counted
};
// The method's visibility (channel 0) against the reference's `channel` over its penumbra,
// leaving out `exclude` (e.g. outside_method_mask).
PenumbraError penumbra_error(const ImageF& visibility, const ImageF& reference, int channel,
                             const std::vector<bool>* exclude = nullptr, int band = kPenumbraBand);

struct LightLeak {
  std::size_t full_shadow = 0;  // masked pixels the soft truth (channel 1) has at exactly 0
  std::size_t leaking = 0;      // of those, the ones the method lights above the threshold
};
LightLeak light_leak(const ImageF& visibility, const ImageF& truth, const std::vector<bool>* exclude = nullptr,
                     float threshold = kLeakThreshold);
// [/penumbra-metric]

// A fixed kernel's footprint in the light's plane: k texels on each side, a texel being the
// map's box over its size along each of the light view's axes (the frustum the stage fitted).
struct KernelFootprint {
  glm::vec3 to_sun{0, 1, 0};             // unit
  glm::vec3 axis_u{1, 0, 0}, axis_v{0, 0, 1};  // unit, across the light
  float width_u = 0, width_v = 0;        // metres: the box is [-w/2, w/2] along each axis
};
KernelFootprint kernel_footprint(const LightFrustum& frustum, int map_size, int kernel);

// The hard visibility averaged over the footprint centred on each pixel's surface point: rays
// toward the sun from the points of the receiver's plane whose projection along the light
// falls in the box (PCF's taps compare the map with that same plane, receiver_plane_gradient),
// on a jittered `strata` x `strata` grid per pixel. Channels as shadow_truth's: 0 the filtered
// visibility, 1 the same, 2 the mask (a surface facing the sun).
ImageF filtered_hard_truth(const RayScene& rays, const FrameCamera& camera, int width, int height,
                           const KernelFootprint& footprint, int strata = 8, std::uint64_t seed = 6);
ImageF cached_filtered_hard_truth(const Scene& scene, const RayScene& rays, const FrameCamera& camera, int width,
                                  int height, const KernelFootprint& footprint, int strata = 8);

}  // namespace lp::ch06
