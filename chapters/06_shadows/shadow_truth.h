#pragma once
// Chapter 06's ground truth: the sun's visibility per pixel, ray traced with Embree over
// every triangle (common/raytrace.h), with none of the shadow map's shortcuts: no light
// frustum, no depth map, no bias beyond the ray tracer's own spawn offset.
//   hard: one occlusion ray per pixel from the surface point the pixel sees, toward the sun.
//   soft: the sun as a disk of directions of angular radius `angular_radius` (the real sun
//         is 0.27 degrees), `samples` stratified directions per pixel, the fraction that
//         reaches the sky: what the filtered methods approximate.
#include <cstdint>

#include <glm/glm.hpp>

#include "chapters/06_shadows/shadow_math.h"
#include "common/camera.h"
#include "common/image.h"
#include "common/raytrace.h"
#include "common/scene.h"

namespace lp::ch06 {

struct TruthSettings {
  float angular_radius = kSunAngularRadius;  // radians, the soft truth's sun disk (PCSS's light, shadow_math.h)
  int samples = 64;              // the soft truth's rays per pixel (a square number is stratified exactly)
  std::uint64_t seed = 6;
};

// Channels: 0 hard visibility (0 or 1), 1 soft visibility, 2 the mask (1 where the sun
// reaches: a surface, not the sky, facing the sun). Top row first, like ImageF.
ImageF shadow_truth(const Scene& scene, const RayScene& rays, const FrameCamera& camera, int width, int height,
                    glm::vec3 sun_direction, const TruthSettings& settings = {});
// The same, through the on-disk cache (common/raytrace.h's cached_image).
ImageF cached_shadow_truth(const Scene& scene, const RayScene& rays, const FrameCamera& camera, int width, int height,
                           glm::vec3 sun_direction, const TruthSettings& settings = {});

// [spot-truth]
// A spot light's hard shadows: one occlusion ray per pixel from the surface point toward the
// light's position. Channels as shadow_truth's: 0 visibility, 1 the same (a point light has no
// penumbra), 2 the mask: a surface facing the light, inside its outer cone (and its range).
// A point light's the same, with no cone.
ImageF spot_shadow_truth(const RayScene& rays, const FrameCamera& camera, int width, int height, const Light& spot);
// [/spot-truth]

// [shadow-error]
// A method's visibility (one channel, top row first) against a truth channel over the mask.
struct VisibilityError {
  double mean_abs = 0;    // mean |v - truth|
  double p99 = 0;         // 99th percentile of |v - truth|
  double wrong = 0;       // fraction of pixels with |v - truth| > 0.5 (hard shadows: on the wrong side)
  std::size_t pixels = 0; // pixels in the mask
};
VisibilityError visibility_error(const ImageF& visibility, const ImageF& truth, int truth_channel,
                                 const std::vector<bool>* exclude = nullptr);
// Pixels whose 3x3 neighbourhood in the hard truth holds both lit and shadowed pixels, or
// that border the mask: the shadow edges, where a map of finite resolution may differ.
std::vector<bool> hard_edge_pixels(const ImageF& truth, int radius = 1);
// [/shadow-error]

// [shimmer]
// Shimmer: how many pixels change sides between two frames of a moving camera. A pixel counts
// where both frames' truths hold it in their masks and neither method picture is the blue of
// the sky or a surface facing away (show_visibility.frag); it flips where its hard visibility
// (channel 0, above or below 0.5) differs between the frames, for the method and for the truth.
// The truth's own flips are the shadow edges sweeping over the pixels as the camera moves; a
// map adds its own when its texel grid moves in the world.
struct Flips {
  std::size_t method = 0, truth = 0, pixels = 0;
};
Flips visibility_flips(const ImageF& method_a, const ImageF& method_b, const ImageF& truth_a, const ImageF& truth_b);
// [/shimmer]

// A direction within `angular_radius` of `axis`, uniform over the cone's solid angle, from
// (u, v) in [0, 1)^2.
glm::vec3 sample_cone(glm::vec3 axis, float angular_radius, float u, float v);

}  // namespace lp::ch06
