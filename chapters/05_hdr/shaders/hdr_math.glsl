// The maths of the HDR stage in GLSL: the same formulas as hdr_math.h (the C++ copy the
// unit tests hold). Every pass of the chapter includes this file.

const float HALF_MAX = 65504.0;  // the largest finite half float

// The stage's storage buffers, their structs and bindings (shared with the C++).
#include "05_hdr/shaders/hdr_buffers.h"

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// [sanitize-glsl]
// Bit patterns, not isnan()/isinf(): a compiler that assumes arithmetic never makes a NaN
// may fold isnan(x) to false, and this is the one place that must see them.
bool is_nan(float x) { return (floatBitsToUint(x) & 0x7fffffffu) > 0x7f800000u; }

// NaN anywhere: invalid (0, and valid = false). +Inf and anything above 65504: 65504.
// Negative and -Inf: 0. See hdr_math.h for why.
vec3 sanitize(vec3 c, out bool valid) {
  valid = !(is_nan(c.r) || is_nan(c.g) || is_nan(c.b));
  if (!valid) return vec3(0.0);
  return clamp(c, vec3(0.0), vec3(HALF_MAX));
}
// [/sanitize-glsl]

float log_luminance(vec3 sanitized_rgb, float delta) { return log(delta + luminance(sanitized_rgb)); }

// [operators-glsl]
#define OP_CLAMP 0
#define OP_REINHARD 1
#define OP_REINHARD_EXTENDED 2
#define OP_ACES 3

// Each function a reader writes in an exercise (chapters/05_hdr/exercises/) stands in for
// the one here when `--exercise K` defines its name (common/app.h, Exercise).
#ifdef EXERCISE_REINHARD_EXTENDED
#include EXERCISE_REINHARD_EXTENDED
#else
vec3 reinhard_extended(vec3 x, float white) { return min(x * (1.0 + x / (white * white)) / (1.0 + x), vec3(1.0)); }
#endif

#ifdef EXERCISE_ACES_FIT
#include EXERCISE_ACES_FIT
#else
// Narkowicz's fit of the ACES filmic curve.
vec3 aces_fit(vec3 x) { return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }
#endif

vec3 tonemap(int op, vec3 x, float white) {
  if (op == OP_CLAMP) return min(x, vec3(1.0));
  if (op == OP_REINHARD) return x / (1.0 + x);
  if (op == OP_REINHARD_EXTENDED) return reinhard_extended(x, white);
  return aces_fit(x);  // OP_ACES
}
// [/operators-glsl]

float adapt(float adapted, float target, float dt, float tau) {
  if (tau <= 0.0) return target;
  return adapted + (target - adapted) * (1.0 - exp(-dt / tau));
}

// key / adapted, with the eye adapted no further into the dark than adapt_floor (hdr_math.h).
float exposure_for(float key, float adapted, float adapt_floor) { return key / max(adapted, adapt_floor); }

#ifdef EXERCISE_BRIGHT_PASS
#include EXERCISE_BRIGHT_PASS
#else
vec3 bright_pass(vec3 x, float threshold, float limit) {
  float y = luminance(x);
  if (y <= threshold || y <= 0.0) return vec3(0.0);
  return x * (min(y - threshold, limit) / y);
}
#endif
