#pragma once
// Chapter 07's ground truth: ambient occlusion ray traced on the CPU (common/raytrace.h), with
// the definition every method here approximates,
//   A(p) = (1 / pi) * integral over the hemisphere of V(p, w) (n . w) dw,
// where V is 1 when a ray of length R from p toward w hits nothing. From the surface point each
// pixel sees (the rasteriser's pixel centres), `samples` cosine-weighted rays of length R about
// the GEOMETRIC normal: the hemisphere of the triangle the point lies on, so no ray starts
// below its own surface (a shading normal tilted away from the triangle would send rays into
// it and count the surface as its own occluder). The estimate is the fraction that escape;
// its standard error is sqrt(A (1 - A) / samples) <= 0.5 / sqrt(samples).
#include <cstdint>

#include "common/camera.h"
#include "common/image.h"
#include "common/scene.h"

namespace lp {
class RayScene;
}

namespace lp::ch07 {

struct AoTruthSettings {
  float radius = 0.5f;
  int samples = 512;
  std::uint64_t seed = 0x414fu;
};

inline constexpr float kTruthSky = -1.f;  // pixels that see no surface

// [truth]
// The truth image (one channel, rows top to bottom, kTruthSky where no surface is seen).
ImageF ray_traced_ao(const RayScene& rays, const FrameCamera& camera, int width, int height, const AoTruthSettings& s);
// The same, stored under out/truth-cache/ and recomputed only when the scene, camera, size or
// settings change (common/raytrace.h's cached_image).
ImageF cached_ray_traced_ao(const Scene& scene, const FrameCamera& camera, int width, int height,
                            const AoTruthSettings& s);
// [/truth]

// A cosine-weighted direction about unit n from two uniform numbers (Malley's method: a
// uniform point of the unit disk lifted onto the hemisphere).
glm::vec3 cosine_direction(glm::vec3 n, float u1, float u2);

// [errors]
// A method's AO against the truth over the pixels both see geometry in (the same size).
struct AoErrors {
  double mean_abs = 0, mean_sq = 0, max_abs = 0, mean_signed = 0;  // mean_signed > 0: too bright
  long pixels = 0;
};
AoErrors ao_errors(const ImageF& ao, const ImageF& truth);
// |ao - truth| per pixel (0 on the sky), for error_heatmap.
std::vector<float> ao_error_map(const ImageF& ao, const ImageF& truth);
// [/errors]

}  // namespace lp::ch07
