#pragma once
// Lights at a stated density: the fair benchmark of issue 24. What a pixel costs is the
// number of lights that reach it, so a sweep over the light count means something only when
// that number is held: here every local light is made larger or smaller until the lit
// (pixel, light) pairs per surface pixel are a target density.
#include <functional>
#include <vector>

#include "common/scene.h"

namespace lp::ch09 {

// [scaled-lights]
// Every local light made s times as large: range x s and intensity x s^2, so that its light
// at a given fraction of its range is unchanged and its cut (chapter 03's light_radius) is s
// times as far. Directional lights stay as they are. s must be finite and > 0 (throws Error).
std::vector<Light> scaled_lights(std::vector<Light> lights, float s);
// [/scaled-lights]

// `count` views along a street: `start` moved by `step` metres at a time along its own view
// direction projected on the ground plane (y up), looking the same way.
std::vector<Camera> views_along(const Camera& start, int count, float step);

// The scale whose measured density is `target` (within `tolerance`, relative). `measure(s)`
// returns the lit pairs per surface pixel with the lights scaled by s; it grows with s, as
// s^3 while lights are small next to the scene and more slowly once they span it (faster,
// by chance, on a small image), so each step is a secant in log space (the first one assumes
// s^3), between the bracket's ends once the target lies between two measurements (and is
// monotone: a steep density, lights near their cut on many surfaces at once, then converges
// instead of overshooting). Bounded: at most
// `max_steps` measurements; `met` says whether the target was reached.
struct DensityFit {
  float scale = 1;
  double density = 0;  // measured at `scale`
  int steps = 0;       // measurements taken
  bool met = false;
};
DensityFit fit_density(double target, float start, const std::function<double(float)>& measure,
                       double tolerance = 0.03, int max_steps = 8);

// The median (q = 0.5) or another quantile of `values`, linearly interpolated between the
// nearest ranks (0 for none).
double quantile(std::vector<double> values, double q);

}  // namespace lp::ch09
