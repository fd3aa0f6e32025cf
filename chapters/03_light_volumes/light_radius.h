#pragma once
// How far a light reaches: the distance at which its contribution drops below what the
// output can show. Chapter 01's attenuation is glTF's inverse square times a window that
// reaches zero at the light's `range`; the light's volume is cut where
//
//     peak * window(d) / d^2 = threshold,   peak = max(colour) * intensity,
//
// and the threshold is one 8-bit step of the output, divided by the exposure and by the
// most any material of the scene reflects.
#include "common/scene.h"

namespace lp::ch03 {

// [threshold]
// One step of an 8-bit channel in linear light: the rule the sources use, right for a light
// buffer stored linearly in 8 bits.
inline constexpr float kLinearEightBitStep = 1.f / 256.f;
// Our output is sRGB-encoded, and the encoding is steepest at black (slope 12.92): there a
// linear 1 / (255 * 12.92) already moves the output by one step. Light dropped below this
// changes no output pixel by more than one step per light, however dark the surroundings:
// a pixel that k cut lights reach can lose up to k steps (chapter 05 accounts for that).
inline constexpr float kSrgbFirstStep = 1.f / (255.f * 12.92f);

// What a surface can make of the light arriving at it: the pixel is radiance x n.l x
// (albedo + specular colour x lobe), and the normalised Blinn-Phong lobe peaks at
// (n + 8) / 8. The largest such factor over the scene's materials; 1 for a white matte
// surface, about 250 for the street's glossy window glass.
float peak_reflectance(const Scene& scene);

// The light below which a light is cut: one output step, before the exposure scales the
// light up (chapter 05; until then 1) and the brightest material reflects it.
inline float cut_threshold(float exposure, float peak_reflectance = 1.f, float step = kSrgbFirstStep) {
  return step / (exposure * peak_reflectance);
}
// [/threshold]

// The radius where peak * distance_attenuation(d, range) falls to `threshold` (range <= 0:
// unbounded, as in chapter 01's shader). 0 for a light that gives no light (peak <= 0, or
// not a finite number). Never smaller than the true distance (see the .cpp).
float light_radius(float peak, float range, float threshold);
float light_radius(const Light& light, float threshold);

}  // namespace lp::ch03
