// The neon (line) light in GLSL: the same maths as neon.cpp (the C++ copy the unit tests and
// the ground truth hold), and the packed per-instance data of capsule.h. The entry point,
// neon_light(NeonSurface, NeonGpu, NeonMethod), lights one surface point by one tube: a forward
// pass calls it per fragment and light, a light-volume pass once per covered pixel.
#include "01_forward/shaders/lighting.glsl"

// [neon-glsl-types]
// One tube, packed as in capsule.h: rows[i] is ROW i of the thesis's matrix M.
#include "04_neon/shaders/neon_gpu.h"

// What the shading needs of a surface point. (Not "Surface": chapter 02's G-buffer has one
// of its own, and a light-volume shader includes both; it builds this one from that one.)
struct NeonSurface {
  vec3 position;
  vec3 normal;  // unit
  vec3 to_eye;  // unit
  float exponent;
};

struct NeonMethod {
  int kind;     // NEON_* below
  int samples;  // ground truth: samples along the tube; points: how many point lights
};

struct NeonResult {
  vec3 diffuse, specular;  // light, before albedo and specular colour
};
// [/neon-glsl-types]

const int NEON_GROUND_TRUTH = 0;
const int NEON_SOURCE = 1;
const int NEON_IMPROVED = 2;
const int NEON_POINTS = 3;
const int NEON_REPRESENTATIVE = 4;
const int NEON_ANALYTIC_DIFFUSE = 5;

const float NEON_MIN_LENGTH = 1e-4;

// The tube unpacked (unpack_neon in capsule.cpp).
struct Neon {
  vec3 start, end, centre;
  vec3 axis;        // unit, start -> end (any unit vector for a zero-length tube)
  vec3 door;        // Ri: the first barn door's side
  float len;
  float volume_radius, tube_radius, specular;
  float doors_radius;  // the barn doors' softness scale (neon.h's doors_radius())
  bool caps;
  vec3 power;       // colour x intensity
  vec4 barn_doors;
};

vec3 neon_perpendicular(vec3 v) {
  vec3 other = abs(v.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
  return normalize(cross(v, other));
}

// [neon-unpack-glsl]
Neon neon_unpack(NeonGpu g) {
  Neon t;
  vec3 ri_r = g.rows[0].xyz, rj_h = g.rows[1].xyz, rk_i = g.rows[2].xyz;
  t.volume_radius = length(ri_r);
  float half_length = length(rj_h);
  t.specular = length(rk_i);
  t.door = ri_r / t.volume_radius;
  // A zero-length tube or a zero specular loses a direction; the others rebuild it.
  vec3 rk = t.specular > 0.0 ? rk_i / t.specular : vec3(0.0);
  t.axis = half_length > 0.0 ? rj_h / half_length : (t.specular > 0.0 ? cross(rk, t.door) : neon_perpendicular(t.door));
  t.centre = g.rows[3].xyz;
  t.start = t.centre - t.axis * half_length;
  t.end = t.centre + t.axis * half_length;
  t.len = 2.0 * half_length;
  t.caps = g.rows[3].w > 0.5;
  t.power = vec3(g.rows[0].w, g.rows[1].w, g.rows[2].w);
  t.tube_radius = max(g.extra.x, 1e-4);
  t.doors_radius = g.extra.y;
  t.barn_doors = g.barn_doors;
  return t;
}
// [/neon-unpack-glsl]

// Exercises 1-3 (chapters/04_neon/exercises/) stand in for the functions so marked.
#ifdef EXERCISE_CLOSEST_ON_SEGMENT
#include EXERCISE_CLOSEST_ON_SEGMENT
#else
float neon_closest_on_segment(vec3 p, vec3 a, vec3 b) {
  vec3 ab = b - a;
  float len2 = dot(ab, ab);
  if (len2 < 1e-20) return 0.0;
  return clamp(dot(p - a, ab) / len2, 0.0, 1.0);
}
#endif

// Chapter 01's Blinn-Phong specular (lobe x N.L) of a unit light in direction l.
float neon_specular_lobe(NeonSurface s, vec3 l) {
  vec3 diffuse = vec3(0.0), specular = vec3(0.0);
  blinn_phong(s.normal, s.to_eye, l, vec3(1.0), s.exponent, diffuse, specular);
  return specular.x;
}

vec3 neon_reflection(NeonSurface s) { return 2.0 * dot(s.normal, s.to_eye) * s.normal - s.to_eye; }

// A zero-length tube: a point light of the whole intensity at its centre.
vec2 neon_point_light_terms(NeonSurface s, Neon t) {
  vec3 p = t.centre - s.position;
  float r2 = max(dot(p, p), t.tube_radius * t.tube_radius);
  vec3 l = dot(p, p) > 0.0 ? normalize(p) : s.normal;
  vec3 diffuse = vec3(0.0), specular = vec3(0.0);
  blinn_phong(s.normal, s.to_eye, l, vec3(1.0 / r2), s.exponent, diffuse, specular);
  return vec2(diffuse.x, specular.x);
}

// The tube seen from a shading point x: P(s) - x = d w + s u, ends at s0 <= s1.
struct NeonFrame {
  vec3 u, w;
  float d, s0, s1;
};

NeonFrame neon_frame(vec3 x, Neon t, vec3 normal) {
  NeonFrame f;
  f.u = t.len > 0.0 ? (t.end - t.start) / t.len : vec3(1.0, 0.0, 0.0);
  float along = dot(x - t.start, f.u);
  vec3 to_line = t.start + along * f.u - x;
  float dist = length(to_line);
  if (dist > 1e-7) {
    f.w = to_line / dist;
  } else {
    vec3 p = normal - dot(normal, f.u) * f.u;
    if (dot(p, p) < 1e-12) p = abs(f.u.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
    f.w = normalize(p - dot(p, f.u) * f.u);
  }
  f.d = max(dist, t.tube_radius);
  f.s0 = -along;
  f.s1 = t.len - along;
  return f;
}

// Keeps the part of the tube above the tangent plane: N . (d w + s u) > 0.
bool neon_clip_to_horizon(NeonFrame f, vec3 normal, out float s0, out float s1) {
  float nw = f.d * dot(normal, f.w), nu = dot(normal, f.u);
  s0 = f.s0;
  s1 = f.s1;
  if (abs(nu) < 1e-7) {
    if (nw <= 0.0) return false;
  } else if (nu > 0.0) {
    s0 = max(s0, -nw / nu);
  } else {
    s1 = min(s1, -nw / nu);
  }
  return s1 > s0;
}

// --- The methods, for a tube of unit intensity: vec2(diffuse, specular) --------------------

// [ground-truth-glsl]
vec2 neon_ground_truth(NeonSurface s, Neon t, int samples) {
  if (t.len < NEON_MIN_LENGTH) return neon_point_light_terms(s, t);
  NeonFrame f = neon_frame(s.position, t, s.normal);
  float s0, s1;
  if (!neon_clip_to_horizon(f, s.normal, s0, s1)) return vec2(0.0);
  float step = (s1 - s0) / float(samples);
  float rho2 = t.tube_radius * t.tube_radius;
  vec3 diffuse = vec3(0.0), specular = vec3(0.0);
  for (int i = 0; i < samples; ++i) {
    vec3 p = f.d * f.w + (s0 + (float(i) + 0.5) * step) * f.u;  // sample - x
    float r2 = dot(p, p);
    blinn_phong(s.normal, s.to_eye, p / sqrt(r2), vec3(step / t.len / max(r2, rho2)), s.exponent, diffuse, specular);
  }
  return vec2(diffuse.x, specular.x);
}
// [/ground-truth-glsl]

#ifdef EXERCISE_ANALYTIC_DIFFUSE
#include EXERCISE_ANALYTIC_DIFFUSE
#else
// [analytic-diffuse-glsl]
float neon_analytic_diffuse(NeonSurface s, Neon t) {
  if (t.len < NEON_MIN_LENGTH) return neon_point_light_terms(s, t).x;
  NeonFrame f = neon_frame(s.position, t, s.normal);
  float s0, s1;
  if (!neon_clip_to_horizon(f, s.normal, s0, s1)) return 0.0;
  float d = f.d, r0 = sqrt(d * d + s0 * s0), r1 = sqrt(d * d + s1 * s1);
  float span = s1 - s0, sum = s0 + s1;
  float dsin = s0 * s1 <= 0.0 ? s1 / r1 - s0 / r0 : d * d * span * sum / (r0 * r1 * (s1 * r0 + s0 * r1));
  float dcos = d * span * sum / (r0 * r1 * (r0 + r1));
  float nw = dot(s.normal, f.w), nu = dot(s.normal, f.u);
  return max(0.0, (nw * dsin + nu * dcos) / (t.len * d));
}
// [/analytic-diffuse-glsl]
#endif

// Gauss-Legendre nodes and weights (positive halves of the symmetric 4- and 8-point rules).
const float NEON_X4[2] = float[2](0.33998104, 0.86113631);
const float NEON_W4[2] = float[2](0.65214515, 0.34785485);
const float NEON_X8[4] = float[4](0.18343464, 0.52553241, 0.79666648, 0.96028986);
const float NEON_W8[4] = float[4](0.36268378, 0.31370665, 0.22238103, 0.10122854);

vec3 neon_direction(NeonFrame f, float phi) { return cos(phi) * f.w + sin(phi) * f.u; }
float neon_lobe_at(NeonSurface s, NeonFrame f, float phi) { return neon_specular_lobe(s, neon_direction(f, phi)); }

float neon_gauss_legendre(NeonSurface s, NeonFrame f, float lo, float hi, int nodes) {
  if (hi <= lo) return 0.0;
  float mid = 0.5 * (lo + hi), half_width = 0.5 * (hi - lo), sum = 0.0;
  for (int i = 0; i < nodes / 2; ++i) {
    float x = nodes == 4 ? NEON_X4[i] : NEON_X8[i], w = nodes == 4 ? NEON_W4[i] : NEON_W8[i];
    sum += w * (neon_lobe_at(s, f, mid - half_width * x) + neon_lobe_at(s, f, mid + half_width * x));
  }
  return sum * half_width;
}

// d/dphi and d2/dphi2 of log(lobe x N.l) as l turns along the tube.
vec2 neon_log_specular_slope(NeonSurface s, vec3 l, vec3 m) {
  float nl = max(dot(s.normal, l), 1e-4), nm = dot(s.normal, m), nv = dot(s.normal, s.to_eye);
  float vl = dot(s.to_eye, l), vm = dot(s.to_eye, m);
  float nh = max(nl + nv, 1e-6), hh = max(2.0 + 2.0 * vl, 1e-6);
  float d1 = s.exponent * (nm / nh - vm / hh) + nm / nl;
  float d2 = s.exponent * (-nl / nh - nm * nm / (nh * nh) + vl / hh + 2.0 * vm * vm / (hh * hh)) - 1.0 - nm * nm / (nl * nl);
  return vec2(d1, d2);
}

// [improved-glsl]
vec2 neon_improved(NeonSurface s, Neon t) {
  if (t.len < NEON_MIN_LENGTH) return neon_point_light_terms(s, t);
  vec2 terms = vec2(neon_analytic_diffuse(s, t), 0.0);
  NeonFrame f = neon_frame(s.position, t, s.normal);
  float s0, s1;
  if (!neon_clip_to_horizon(f, s.normal, s0, s1)) return terms;
  float d = f.d, phi0 = atan(s0, d), phi1 = atan(s1, d), span = phi1 - phi0;
  // 1. Start at the better of: the point closest in angle to the reflection ray, and the
  //    point where N.l peaks.
  vec3 R = neon_reflection(s);
  float a = d * dot(R, f.w), b = dot(R, f.u);
  float s_r;
  if (a > 1e-12) {
    s_r = clamp(b * d * d / a, s0, s1);
  } else {
    float c0 = (a + b * s0) / sqrt(d * d + s0 * s0), c1 = (a + b * s1) / sqrt(d * d + s1 * s1);
    s_r = c0 >= c1 ? s0 : s1;
  }
  float phi_r = atan(s_r, d);
  float phi_n = clamp(atan(dot(s.normal, f.u), dot(s.normal, f.w)), phi0, phi1);
  float f_r = neon_lobe_at(s, f, phi_r), f_n = neon_lobe_at(s, f, phi_n);
  float peak = f_r >= f_n ? phi_r : phi_n, best = max(f_r, f_n);
  // 2. Two Newton steps on log(lobe x N.l) to the peak; the curvature gives its width.
  vec2 slope;
  for (int step = 0;; ++step) {
    slope = neon_log_specular_slope(s, neon_direction(f, peak), -sin(peak) * f.w + cos(peak) * f.u);
    if (step == 2) break;
    float limit = 0.25 * span;
    float move = slope.y < 0.0 ? -slope.x / slope.y : (slope.x >= 0.0 ? limit : -limit);
    float next = clamp(peak + clamp(move, -limit, limit), phi0, phi1);
    float value = neon_lobe_at(s, f, next);
    if (value < best) break;
    best = value;
    peak = next;
  }
  float sigma = slope.y < 0.0 ? 1.0 / sqrt(-slope.y) : span;
  // 3. 8 Gauss-Legendre nodes on peak +- 3.5 sigma, 4 on each side of it.
  float lo = max(phi0, peak - 3.5 * sigma), hi = min(phi1, peak + 3.5 * sigma);
  float sum = neon_gauss_legendre(s, f, lo, hi, 8) + neon_gauss_legendre(s, f, phi0, lo, 4) +
              neon_gauss_legendre(s, f, hi, phi1, 4);
  terms.y = sum / (t.len * d);
  return terms;
}
// [/improved-glsl]

#ifdef EXERCISE_NEON_POINTS
#include EXERCISE_NEON_POINTS
#else
// [points-glsl]
vec2 neon_points(NeonSurface s, Neon t, int count) {
  // count chapter-01 point lights along the tube, sharing its intensity.
  vec3 diffuse = vec3(0.0), specular = vec3(0.0);
  for (int i = 0; i < count; ++i) {
    GpuLight point;
    point.position_type = vec4(mix(t.start, t.end, (float(i) + 0.5) / float(count)), LIGHT_POINT);
    point.direction_range = vec4(0.0, 0.0, -1.0, 0.0);
    point.radiance = vec4(vec3(1.0 / float(count)), 0.0);
    point.spot = vec4(0.0);
    vec3 to_light, radiance;
    light_incident(point, s.position, to_light, radiance);
    blinn_phong(s.normal, s.to_eye, to_light, radiance, s.exponent, diffuse, specular);
  }
  return vec2(diffuse.x, specular.x);
}
// [/points-glsl]
#endif

vec2 neon_representative_point(NeonSurface s, Neon t) {
  // Karis 2013: closed-form diffuse with "+ 2", specular from the point of the tube nearest
  // (in distance) to the reflection ray's line, lobe widened by alpha / alpha'.
  float rho = t.tube_radius;
  vec3 l0 = t.start - s.position, l1 = t.end - s.position;
  float d0 = max(length(l0), rho), d1 = max(length(l1), rho);
  float cosines = dot(s.normal, l0) / (2.0 * d0) + dot(s.normal, l1) / (2.0 * d1);
  vec2 terms;
  terms.x = 2.0 * clamp(cosines, 0.0, 1.0) / (d0 * d1 + dot(l0, l1) + 2.0);
  vec3 R = neon_reflection(s), ld = l1 - l0;
  float r_ld = dot(R, ld), denom = dot(ld, ld) - r_ld * r_ld;
  float k = denom > 1e-6 * dot(ld, ld) ? (dot(R, l0) * r_ld - dot(l0, ld)) / denom : 0.0;
  vec3 p = l0 + clamp(k, 0.0, 1.0) * ld;
  float dist = max(length(p), rho);
  float alpha = sqrt(2.0 / (s.exponent + 2.0));
  float widened = min(1.0, alpha + 0.5 * t.len / (2.0 * dist));
  terms.y = neon_specular_lobe(s, p / dist) * (alpha / widened) / (dist * dist);
  return terms;
}

// [source-glsl]
vec2 neon_source(NeonSurface s, Neon t) {
  // The thesis's listings 4.11 and 4.12, its radius and brightness fitted as in fit_source().
  float d1 = max(0.5 * t.len, 0.05), d2 = 4.0 * d1;
  float e1 = 1.0 / (d1 * sqrt(d1 * d1 + 0.25 * t.len * t.len)), e2 = 1.0 / (d2 * sqrt(d2 * d2 + 0.25 * t.len * t.len));
  float q = sqrt(e1 / e2);
  float radius = (q * d2 - d1) / (q - 1.0);
  float scale = e1 / ((1.0 - d1 / radius) * (1.0 - d1 / radius));
  vec3 u = t.len > 0.0 ? (t.end - t.start) / t.len : vec3(1.0, 0.0, 0.0);
  // Diffuse: the closest point and a normal bent towards it.
  vec3 closest = mix(t.start, t.end, neon_closest_on_segment(s.position, t.start, t.end));
  vec3 to_light = closest - s.position;
  float dist = length(to_light);
  if (dist > radius) return vec2(0.0);
  vec3 cp = dist > 0.0 ? to_light / dist : s.normal;
  float h = clamp(dist / radius, 0.0, 1.0);
  vec3 bent = normalize(s.normal + cp * (1.0 - h * h) * 0.5);
  float attenuation = clamp(dot(cp, bent), 0.0, 1.0) * (1.0 - h);
  vec2 terms;
  terms.x = scale * attenuation * attenuation;
  // Specular: closest points of the tube's line and the reflection line.
  vec3 R = neon_reflection(s), start = t.start - s.position;
  float a = dot(u, R), b = dot(u, start), c = dot(R, start);
  float aa = 1.0 - a * a;
  bool parallel = aa == 0.0;
  float sc = parallel ? 0.0 : (a * c - b) / aa;
  sc = sc > 0.0 && sc <= t.len ? sc : (sc > t.len ? t.len : 0.0);
  vec3 on_tube = t.start + sc * u, to_tube = on_tube - s.position;
  float tc = dot(R, to_tube);
  vec3 on_ray = s.position + tc * R;
  float dot_lr = length(to_tube) > 0.0 ? clamp(dot(normalize(to_tube), R), 0.0, 1.0) : 0.0;
  float miss = max(length(on_tube - on_ray) / radius, 1e-6);
  float spread = 1.0 + tc / radius;
  terms.y = scale * dot_lr * clamp(1.0 - pow(miss, spread), 0.0, 1.0);
  return terms;
}
// [/source-glsl]

// --- The volume and the barn doors ----------------------------------------------------------

float neon_volume_mask(vec3 x, Neon t) {
  vec3 c = mix(t.start, t.end, neon_closest_on_segment(x, t.start, t.end));
  if (length(x - c) > t.volume_radius) return 0.0;
  if (!t.caps && t.len >= NEON_MIN_LENGTH) {
    float along = dot(x - t.start, (t.end - t.start) / t.len);
    if (along < 0.0 || along > t.len) return 0.0;
  }
  return 1.0;
}

float neon_barn_doors(vec3 x, Neon t) {
  vec4 doors = t.barn_doors;  // distance, count, transmittance, softness
  if (doors.y <= 0.0) return 1.0;
  vec3 v = x - mix(t.start, t.end, neon_closest_on_segment(x, t.start, t.end));
  float dist = max(length(v), t.tube_radius);
  if (dist <= doors.x) return 1.0;
  vec3 u = t.len > 0.0 ? (t.end - t.start) / t.len : vec3(0.0);
  vec3 across = v - dot(v, u) * u;
  float cos_angle = dot(across, across) > 1e-12 ? dot(t.door, normalize(across)) : 0.0;
  float pattern = cos(doors.y * acos(clamp(cos_angle, -1.0, 1.0)));
  float open = clamp(2.0 * doors.z - pattern, 0.0, 1.0);
  float sharpness = clamp(doors.w * t.doors_radius / dist, 1e-3, 1e3);
  return open <= 0.0 ? 0.0 : pow(open, sharpness);
}

// [neon-light-glsl]
NeonResult neon_light(NeonSurface s, NeonGpu light, NeonMethod method) {
  Neon t = neon_unpack(light);
  NeonResult result = NeonResult(vec3(0.0), vec3(0.0));
  // The truth is not cut: no radius, only a cylinder's ends (as neon.cpp).
  Neon bounds = t;
  if (method.kind == NEON_GROUND_TRUTH) bounds.volume_radius = 3.0e38;
  float mask = neon_volume_mask(s.position, bounds) * neon_barn_doors(s.position, t);
  if (mask == 0.0) return result;
  vec2 terms;
  if (method.kind == NEON_GROUND_TRUTH) terms = neon_ground_truth(s, t, method.samples);
  else if (method.kind == NEON_SOURCE) terms = neon_source(s, t);
  else if (method.kind == NEON_IMPROVED) terms = neon_improved(s, t);
  else if (method.kind == NEON_POINTS) terms = neon_points(s, t, method.samples);
  else if (method.kind == NEON_REPRESENTATIVE) terms = neon_representative_point(s, t);
  else terms = vec2(neon_analytic_diffuse(s, t), 0.0);
  result.diffuse = t.power * (terms.x * mask);
  result.specular = t.power * (terms.y * t.specular * mask);
  return result;
}
// [/neon-light-glsl]
