// Chapter 07's formulas that have C++ twins in ao_math.h, in GLSL. ssao.comp and blur.comp
// include this file, and so does tests/unit/test_07_twins_gl.cpp, which runs each against its
// twin.

const float PI = 3.14159265358979;

// A right-handed orthonormal basis around unit n (Duff et al. 2017): chapter 03's
// basis_around's first two columns.
void basis(vec3 n, out vec3 t, out vec3 b) {
  float sign_z = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (sign_z + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0 + sign_z * n.x * n.x * a, sign_z * c, -sign_z * n.x);
  b = vec3(c, sign_z + n.y * n.y * a, -n.y);
}

// A kernel point reflected about the plane whose normal is the noise vector r (in the tangent
// plane): its height above the surface and its length stay.
vec3 reflect_about(vec3 k, vec3 r) { return k - 2.0 * dot(k, r) * r; }

// The classic's range check: an occluder whose depth is `gap` from the pixel's counts fully
// within the radius and fades beyond it (a column before a distant wall).
// With --exercise 1 the reader's range_weight (chapters/07_ssao/exercises/range_check.glsl) stands in.
#ifdef EXERCISE_RANGE_CHECK
#include EXERCISE_RANGE_CHECK
#else
float range_weight(float radius, float gap) { return smoothstep(0.0, 1.0, radius / max(abs(gap), 1e-6)); }
#endif

// The 2D disk's spiral: sample i of n at radius sqrt((i + 0.5) / n) of the disk's and angle
// i times the golden angle, plus `turn`; (radius, angle).
vec2 spiral_polar(int i, int n, float turn) {
  return vec2(sqrt((float(i) + 0.5) / float(n)), 2.39996323 * float(i) + turn);
}

// The disk's two occlusion terms for a receiver p (normal np) and an emitter disk at e
// (normal ne, area A): Bunnell's and the cosine-weighted form factor (ao_math.h [bunnell]).
float bunnell_occlusion(vec3 p, vec3 np, vec3 e, vec3 ne, float area) {
  vec3 v = e - p;
  float d2 = dot(v, v);
  if (d2 <= 0.0 || area <= 0.0) return 0.0;
  v *= inversesqrt(d2);
  return (1.0 - inversesqrt(1.0 + area / (PI * d2))) * abs(dot(ne, v)) * clamp(4.0 * dot(np, v), 0.0, 1.0);
}
// With --exercise 3 the reader's form factor (chapters/07_ssao/exercises/disk_form_factor.glsl) stands in.
#ifdef EXERCISE_DISK_FORM_FACTOR
#include EXERCISE_DISK_FORM_FACTOR
#else
float form_factor_occlusion(vec3 p, vec3 np, vec3 e, vec3 ne, float area) {
  vec3 v = e - p;
  float d2 = dot(v, v);
  if (d2 <= 0.0 || area <= 0.0) return 0.0;
  v *= inversesqrt(d2);
  return area * abs(dot(ne, v)) * max(dot(np, v), 0.0) / (PI * d2 + area);
}
#endif

// The blur's similarity: a neighbour at view depth z with normal n counts (1) when within
// depth_threshold of the centre's depth zc, relative to it, and within acos(normal_threshold)
// of its normal nc.
float bilateral_weight(float zc, float z, vec3 nc, vec3 n, float depth_threshold, float normal_threshold) {
  return (abs(z - zc) <= depth_threshold * zc && dot(n, nc) >= normal_threshold) ? 1.0 : 0.0;
}

// [gtao-integral]
float acos_clamped(float x) { return acos(clamp(x, -1.0, 1.0)); }
// The horizon cosine one occluder point q gives the receiver p: its elevation toward the view
// vector, blended toward the slice's lowest value `low` by the falloff's weight.
float gtao_horizon(vec3 p, vec3 q, vec3 normal, vec3 view_vec, float low, float falloff_mul, float falloff_add,
                   float min_height) {
  vec3 delta = q - p;
  float dist = length(delta);
  if (dist <= 0.0) return low;
  float weight = clamp(dist * falloff_mul + falloff_add, 0.0, 1.0);
  // as the classic bias: a point less than min_height (bias x R) above the tangent plane is the
  // surface itself, its depth rounded (D24 far from the camera), not an occluder
  if (dot(delta, normal) < min_height) weight = 0.0;
  return mix(low, dot(delta / dist, view_vec), weight);
}
// The cosine-weighted visibility of a slice from the view vector to the horizon angle h, for
// the projected normal at angle n (cos_n = cos n): the integral of |sin t| cos(t - n) dt over
// t between 0 and h, in closed form.
float gtao_arc(float h, float n, float cos_n) { return (cos_n + 2.0 * h * sin(n) - cos(2.0 * h - n)) / 4.0; }
// [/gtao-integral]
