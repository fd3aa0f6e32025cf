// The book's lighting model in GLSL: the same formulas as blinn_phong.h (the C++ copy the
// tests and the ground truth use). Later chapters include this file.

// struct GpuLight, one file shared with C++ (light_buffer.h)
#include "01_forward/shaders/gpu_light.h"

const float LIGHT_DIRECTIONAL = 0.0;
const float LIGHT_POINT = 1.0;
const float LIGHT_SPOT = 2.0;

// Each function a reader writes in an exercise (chapters/01_forward/exercises/ and, for the
// range window, 03_light_volumes/exercises/) stands in
// for the one here when `--exercise K` defines its name (common/app.h, Exercise).
#ifdef EXERCISE_RANGE_WINDOW
#include EXERCISE_RANGE_WINDOW
#else
// glTF's range window: 1 at the light, smoothly 0 at `range` (1 everywhere without one).
float range_window(float distance, float range) {
  float window = 1.0;
  if (range > 0.0) {
    float ratio = distance / range;
    window = clamp(1.0 - ratio * ratio * ratio * ratio, 0.0, 1.0);
    window *= window;
  }
  return window;
}
#endif

#ifdef EXERCISE_DISTANCE_ATTENUATION
#include EXERCISE_DISTANCE_ATTENUATION
#else
float distance_attenuation(float distance, float range) {
  float d2 = max(distance * distance, 1e-4);
  return range_window(distance, range) / d2;
}
#endif

#ifdef EXERCISE_SPOT_CONE
#include EXERCISE_SPOT_CONE
#else
// A spot's cone: 1 inside the inner angle, 0 outside the outer, smooth between
// (spot.x = cos(outer), spot.y = 1 / (cos(inner) - cos(outer))).
float spot_cone(GpuLight light, vec3 to_light) {
  float t = clamp((dot(-to_light, light.direction_range.xyz) - light.spot.x) * light.spot.y, 0.0, 1.0);
  return t * t;
}
#endif

// Direction to the light (xyz) and the radiance arriving at `position`.
void light_incident(GpuLight light, vec3 position, out vec3 to_light, out vec3 radiance) {
  if (light.position_type.w == LIGHT_DIRECTIONAL) {
    to_light = -light.direction_range.xyz;
    radiance = light.radiance.rgb;
    return;
  }
  vec3 d = light.position_type.xyz - position;
  float distance = length(d);
  to_light = distance > 0.0 ? d / distance : vec3(0.0, 1.0, 0.0);
  float a = distance_attenuation(distance, light.direction_range.w);
  if (light.position_type.w == LIGHT_SPOT) a *= spot_cone(light, to_light);
  radiance = light.radiance.rgb * a;
}

#ifdef EXERCISE_BLINN_PHONG
#include EXERCISE_BLINN_PHONG
#else
// [blinn-phong-glsl]
// Lambert + normalised Blinn-Phong for one light; diffuse and specular kept apart.
void blinn_phong(vec3 n, vec3 to_eye, vec3 to_light, vec3 radiance, float exponent,
                 inout vec3 diffuse, inout vec3 specular) {
  float n_dot_l = dot(n, to_light);
  if (n_dot_l <= 0.0) return;
  diffuse += radiance * n_dot_l;
  if (to_light + to_eye == vec3(0.0)) return;  // the eye opposite the light: no half vector
  vec3 h = normalize(to_light + to_eye);
  float n_dot_h = max(dot(n, h), 0.0);
  float lobe = (exponent + 8.0) / 8.0 * pow(n_dot_h, exponent);
  specular += radiance * (lobe * n_dot_l);
}
// [/blinn-phong-glsl]
#endif
