#include "chapters/04_neon/neon.h"

#include <algorithm>
#include <limits>
#include <cmath>
#include <numbers>

#include "chapters/01_forward/blinn_phong.h"
#include "common/error.h"

namespace lp::ch04 {

namespace {

// Shorter tubes are treated as point lights (the limit of every formula as L -> 0).
constexpr float kMinLength = 1e-4f;
// Nothing is closer to the axis than this, even a tube declared with radius 0.
float tube_radius(const NeonLight& light) { return std::max(light.radius, 1e-4f); }

float saturate(float x) { return std::clamp(x, 0.f, 1.f); }

// Blinn-Phong specular (lobe x N.L) of a unit point light in direction l: chapter 01's model.
float specular_lobe(const NeonSurface& s, const glm::vec3& l) {
  return ch01::blinn_phong(s.normal, s.to_eye, l, glm::vec3(1), s.exponent).specular.x;
}

// A zero-length tube: a point light of the whole intensity at its centre.
Terms point_light_terms(const NeonSurface& s, const NeonLight& light) {
  glm::vec3 p = 0.5f * (light.start + light.end) - s.position;
  float r2 = std::max(glm::dot(p, p), tube_radius(light) * tube_radius(light));
  glm::vec3 l = glm::dot(p, p) > 0 ? glm::normalize(p) : s.normal;
  ch01::Reflected r = ch01::blinn_phong(s.normal, s.to_eye, l, glm::vec3(1.f / r2), s.exponent);
  return {r.diffuse.x, r.specular.x};
}

glm::vec3 reflection(const NeonSurface& s) { return 2.f * glm::dot(s.normal, s.to_eye) * s.normal - s.to_eye; }

}  // namespace

Method method_from_name(const std::string& name) {
  for (size_t i = 0; i < kMethodNames.size(); ++i)
    if (kMethodNames[i] == name) return static_cast<Method>(i);
  throw Error("unknown neon method '" + name + "'");
}

// --- Geometry ------------------------------------------------------------------------------

float closest_on_segment(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b) {
  glm::vec3 ab = b - a;
  float len2 = glm::dot(ab, ab);
  if (len2 < 1e-20f) return 0.f;
  return saturate(glm::dot(p - a, ab) / len2);
}

// [closest-segment-ray]
SegmentRayClosest closest_segment_ray(const glm::vec3& a, const glm::vec3& b, const glm::vec3& origin,
                                      const glm::vec3& dir) {
  // Minimise |a + s e - (origin + t dir)|^2 over s in [0, 1], t >= 0, with e = b - a.
  SegmentRayClosest c;
  glm::vec3 e = b - a, r = a - origin;
  float ee = glm::dot(e, e), f = glm::dot(dir, r);  // f: where a projects onto the ray
  if (ee < 1e-20f) {                                // a point: project it onto the ray
    c.s = 0;
    c.t = std::max(f, 0.f);
  } else {
    float g = glm::dot(e, r), h = glm::dot(e, dir);
    // The textbook s = (h f - g) / (ee - h^2) subtracts nearly equal numbers when the
    // directions are nearly parallel. The same ratio from cross products loses nothing:
    // ee - h^2 = |e x dir|^2 and h f - g = (e x dir) . (dir x r).
    glm::vec3 across = glm::cross(e, dir);
    float denom = glm::dot(across, across);
    // Parallel (to 1e-6 rad): every point of the overlap is equally close; take the one
    // nearest the ray's origin.
    c.parallel = denom <= 1e-12f * ee;
    c.s = c.parallel ? saturate(-g / ee) : saturate(glm::dot(across, glm::cross(dir, r)) / denom);
    c.t = f + h * c.s;  // the ray's point closest to a + s e
    if (c.t < 0) {      // behind the origin: the ray's closest point is the origin itself
      c.t = 0;
      c.s = saturate(-g / ee);
    }
  }
  c.on_segment = a + c.s * e;
  c.on_ray = origin + c.t * dir;
  c.distance = glm::length(c.on_segment - c.on_ray);
  return c;
}
// [/closest-segment-ray]

LineFrame line_frame(const glm::vec3& x, const NeonLight& light, const glm::vec3& normal) {
  LineFrame f;
  glm::vec3 axis = light.end - light.start;
  float length = glm::length(axis);
  if (length > 0) f.u = axis / length;
  float along = glm::dot(x - light.start, f.u);
  glm::vec3 to_line = light.start + along * f.u - x;
  float dist = glm::length(to_line);
  if (dist > 1e-7f) {
    f.w = to_line / dist;
  } else {  // on the axis line (inside the glass): any perpendicular, the one nearest the normal
    glm::vec3 p = normal - glm::dot(normal, f.u) * f.u;
    if (glm::dot(p, p) < 1e-12f) p = std::abs(f.u.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    f.w = glm::normalize(p - glm::dot(p, f.u) * f.u);
  }
  f.d = std::max(dist, tube_radius(light));
  f.s0 = -along;
  f.s1 = length - along;
  return f;
}

// [horizon-clip]
bool clip_to_horizon(const LineFrame& f, const glm::vec3& normal, float& s0, float& s1) {
  // N . (d w + s u) > 0  <=>  nw + s nu > 0: one linear inequality in s.
  float nw = f.d * glm::dot(normal, f.w), nu = glm::dot(normal, f.u);
  s0 = f.s0;
  s1 = f.s1;
  if (std::abs(nu) < 1e-7f) {
    if (nw <= 0) return false;
  } else if (nu > 0) {
    s0 = std::max(s0, -nw / nu);
  } else {
    s1 = std::min(s1, -nw / nu);
  }
  return s1 > s0;
}
// [/horizon-clip]

// --- Extent --------------------------------------------------------------------------------

float max_irradiance_at(const NeonLight& light, float r) {
  // (I/L) (2/r) atan(L/2r) = (I/r^2) atan(x)/x with x = L/2r, which stays finite as L -> 0.
  float x = light.length() / (2.f * r);
  float atan_over_x = x < 1e-4f ? 1.f - x * x / 3.f : std::atan(x) / x;
  float brightest = std::max({light.color.r, light.color.g, light.color.b}) * light.intensity;
  return brightest * atan_over_x / (r * r);
}

// [volume-radius]
float volume_radius(const NeonLight& light, float threshold) {
  // max_irradiance_at falls monotonically with r: bisect (in log r) for where it meets the threshold.
  float lo = tube_radius(light), hi = 1e5f;
  if (max_irradiance_at(light, lo) <= threshold) return lo;
  for (int i = 0; i < 64; ++i) {
    float mid = std::sqrt(lo * hi);
    (max_irradiance_at(light, mid) > threshold ? lo : hi) = mid;
  }
  return hi;
}
// [/volume-radius]

float volume_mask(const glm::vec3& x, const NeonLight& light, float radius) {
  float t = closest_on_segment(x, light.start, light.end);
  glm::vec3 c = light.start + t * (light.end - light.start);
  if (glm::length(x - c) > radius) return 0.f;
  float length = light.length();
  if (!light.caps && length >= kMinLength) {  // the cylinder: nothing beyond the ends
    float along = glm::dot(x - light.start, (light.end - light.start) / length);
    if (along < 0 || along > length) return 0.f;
  }
  return 1.f;
}

// [barn-doors]
float barn_doors_mask(const glm::vec3& x, const NeonLight& light, float doors_radius) {
  const BarnDoors& doors = light.barn_doors;
  if (!doors.enabled()) return 1.f;
  float t = closest_on_segment(x, light.start, light.end);
  glm::vec3 v = x - (light.start + t * (light.end - light.start));  // from the tube to x
  float dist = std::max(glm::length(v), tube_radius(light));
  if (dist <= doors.distance) return 1.f;
  // The angle around the axis between the first door and x. (The thesis takes the 3D angle
  // to the closest point; around the axis the doors stay planes through the tube.)
  float length = light.length();
  glm::vec3 u = length > 0 ? (light.end - light.start) / length : glm::vec3(0);
  glm::vec3 across = v - glm::dot(v, u) * u;
  float cos_angle = glm::dot(across, across) > 1e-12f ? glm::dot(light.door_axis, glm::normalize(across)) : 0.f;
  float pattern = std::cos(doors.count * std::acos(std::clamp(cos_angle, -1.f, 1.f)));
  float open = saturate(2.f * doors.transmittance - pattern);  // 1 between the doors
  float sharpness = std::clamp(doors.softness * doors_radius / dist, 1e-3f, 1e3f);  // sharper near the tube
  return open <= 0 ? 0.f : std::pow(open, sharpness);
}
// [/barn-doors]

// --- The methods ---------------------------------------------------------------------------

// [ground-truth]
Terms ground_truth_terms(const NeonSurface& s, const NeonLight& light, int samples) {
  float length = light.length();
  if (length < kMinLength) return point_light_terms(s, light);
  LineFrame f = line_frame(s.position, light, s.normal);
  float s0, s1;
  if (!clip_to_horizon(f, s.normal, s0, s1)) return {};  // the tube is below the horizon
  // Midpoint rule over the visible part: each sample is a point light of intensity
  // (I / L) x its share of the tube, with chapter 01's BRDF.
  float step = (s1 - s0) / static_cast<float>(samples);
  float rho2 = tube_radius(light) * tube_radius(light);
  double diffuse = 0, specular = 0;
  for (int i = 0; i < samples; ++i) {
    glm::vec3 p = f.d * f.w + (s0 + (static_cast<float>(i) + 0.5f) * step) * f.u;  // sample - x
    float r2 = glm::dot(p, p);
    glm::vec3 radiance(step / length / std::max(r2, rho2));
    ch01::Reflected r = ch01::blinn_phong(s.normal, s.to_eye, p / std::sqrt(r2), radiance, s.exponent);
    diffuse += r.diffuse.x;
    specular += r.specular.x;
  }
  return {static_cast<float>(diffuse), static_cast<float>(specular)};
}
// [/ground-truth]

// [analytic-diffuse]
Terms analytic_diffuse_terms(const NeonSurface& s, const NeonLight& light) {
  float length = light.length();
  if (length < kMinLength) return {point_light_terms(s, light).diffuse, 0.f};
  LineFrame f = line_frame(s.position, light, s.normal);
  float s0, s1;
  if (!clip_to_horizon(f, s.normal, s0, s1)) return {};
  // Seen from x, the tube sweeps the angles phi = atan(s / d); each radian brings
  // (I / L) / d, and N.l = nw cos(phi) + nu sin(phi) integrates to sines and cosines:
  //   E = (I / (L d)) [nw (sin phi1 - sin phi0) + nu (cos phi0 - cos phi1)].
  float d = f.d, r0 = std::sqrt(d * d + s0 * s0), r1 = std::sqrt(d * d + s1 * s1);
  float span = s1 - s0, sum = s0 + s1;
  // sin phi1 - sin phi0 and cos phi0 - cos phi1, rewritten so that nothing cancels when
  // both ends lie on the same side of the foot (far along the axis, or a short tube).
  float dsin = s0 * s1 <= 0 ? s1 / r1 - s0 / r0 : d * d * span * sum / (r0 * r1 * (s1 * r0 + s0 * r1));
  float dcos = d * span * sum / (r0 * r1 * (r0 + r1));
  float nw = glm::dot(s.normal, f.w), nu = glm::dot(s.normal, f.u);
  return {std::max(0.f, (nw * dsin + nu * dcos) / (length * d)), 0.f};
}
// [/analytic-diffuse]

// [improved-specular]
namespace {

// Gauss-Legendre quadrature of f over [lo, hi] with 4 or 8 nodes (the positive half of each
// symmetric rule: nodes and weights).
template <int Nodes, class F>
float gauss_legendre(float lo, float hi, F f) {
  static constexpr float x4[2] = {0.33998104f, 0.86113631f}, w4[2] = {0.65214515f, 0.34785485f};
  static constexpr float x8[4] = {0.18343464f, 0.52553241f, 0.79666648f, 0.96028986f};
  static constexpr float w8[4] = {0.36268378f, 0.31370665f, 0.22238103f, 0.10122854f};
  const float* x = Nodes == 4 ? x4 : x8;
  const float* w = Nodes == 4 ? w4 : w8;
  if (hi <= lo) return 0.f;
  float mid = 0.5f * (lo + hi), half = 0.5f * (hi - lo), sum = 0;
  for (int i = 0; i < Nodes / 2; ++i) sum += w[i] * (f(mid - half * x[i]) + f(mid + half * x[i]));
  return sum * half;
}

// d/dphi and d2/dphi2 of log(lobe x N.l) as l turns along the tube (dl/dphi = m, dm/dphi = -l),
// with lobe = (N.H)^n and N.H = (N.l + N.V) / |l + V|.
glm::vec2 log_specular_slope(const NeonSurface& s, const glm::vec3& l, const glm::vec3& m) {
  const glm::vec3 &n = s.normal, &v = s.to_eye;
  float nl = std::max(glm::dot(n, l), 1e-4f), nm = glm::dot(n, m), nv = glm::dot(n, v);
  float vl = glm::dot(v, l), vm = glm::dot(v, m);
  float nh = std::max(nl + nv, 1e-6f), hh = std::max(2.f + 2.f * vl, 1e-6f);  // hh = |l + V|^2
  float d1 = s.exponent * (nm / nh - vm / hh) + nm / nl;
  float d2 = s.exponent * (-nl / nh - nm * nm / (nh * nh) + vl / hh + 2.f * vm * vm / (hh * hh)) - 1.f - nm * nm / (nl * nl);
  return {d1, d2};
}

}  // namespace

Terms improved_terms(const NeonSurface& s, const NeonLight& light) {
  Terms out = analytic_diffuse_terms(s, light);  // exact, see above
  float length = light.length();
  if (length < kMinLength) return point_light_terms(s, light);
  LineFrame f = line_frame(s.position, light, s.normal);
  float s0, s1;
  if (!clip_to_horizon(f, s.normal, s0, s1)) return out;
  // Per radian of the angle phi = atan(s / d) the tube brings (I / L) / d, so the specular is
  // (I / (L d)) x the integral of F(phi) = lobe x N.l over [phi0, phi1]: no 1/r^2 left in it.
  float d = f.d, phi0 = std::atan2(s0, d), phi1 = std::atan2(s1, d), span = phi1 - phi0;
  auto direction = [&](float phi) { return std::cos(phi) * f.w + std::sin(phi) * f.u; };
  auto F = [&](float phi) { return specular_lobe(s, direction(phi)); };
  // [improved-peak]
  // 1. Where the highlight is. The thesis's idea, asked in angle instead of distance: the
  //    point of the tube whose direction is closest to the reflection ray R. Along the tube
  //    cos(l, R) = (a + b s) / sqrt(d^2 + s^2), whose only maximum is at s = b d^2 / a (a > 0),
  //    else at the better end: no "parallel" case. At grazing angles the N.l factor drags the
  //    peak towards the normal, so the point where N.l peaks is the other candidate.
  glm::vec3 R = reflection(s);
  float a = d * glm::dot(R, f.w), b = glm::dot(R, f.u);
  auto cosine = [&](float t) { return (a + b * t) / std::sqrt(d * d + t * t); };
  float s_r = a > 1e-12f ? std::clamp(b * d * d / a, s0, s1) : (cosine(s0) >= cosine(s1) ? s0 : s1);
  float phi_r = std::atan2(s_r, d);
  float phi_n = std::clamp(std::atan2(glm::dot(s.normal, f.u), glm::dot(s.normal, f.w)), phi0, phi1);
  float f_r = F(phi_r), f_n = F(phi_n);
  float peak = f_r >= f_n ? phi_r : phi_n, best = std::max(f_r, f_n);
  // [/improved-peak]
  // 2. Two Newton steps on log F climb to the peak; its curvature gives the width sigma.
  glm::vec2 slope;
  for (int step = 0;; ++step) {
    slope = log_specular_slope(s, direction(peak), -std::sin(peak) * f.w + std::cos(peak) * f.u);
    if (step == 2) break;
    float limit = 0.25f * span;
    float move = slope.y < 0 ? -slope.x / slope.y : (slope.x >= 0 ? limit : -limit);
    float next = std::clamp(peak + std::clamp(move, -limit, limit), phi0, phi1);
    float value = F(next);
    if (value < best) break;  // Newton overshot (log F is not a parabola): keep what we had
    best = value;
    peak = next;
  }
  float sigma = slope.y < 0 ? 1.f / std::sqrt(-slope.y) : span;
  // [improved-quadrature]
  // 3. Gauss-Legendre on three pieces: 8 nodes on the highlight (peak +- 3.5 sigma), 4 on
  //    each side of it for the tails a wide lobe or a grazing view leaves there.
  float lo = std::max(phi0, peak - 3.5f * sigma), hi = std::min(phi1, peak + 3.5f * sigma);
  float sum = gauss_legendre<8>(lo, hi, F) + gauss_legendre<4>(phi0, lo, F) + gauss_legendre<4>(hi, phi1, F);
  out.specular = sum / (length * d);
  // [/improved-quadrature]
  return out;
}
// [/improved-specular]

// [points]
Terms points_terms(const NeonSurface& s, const NeonLight& light, int count) {
  // count chapter-01 point lights, evenly spaced, sharing the intensity.
  Terms out;
  for (int i = 0; i < count; ++i) {
    Light point{.type = LightType::Point, .intensity = 1.f / static_cast<float>(count),
                .position = glm::mix(light.start, light.end, (static_cast<float>(i) + 0.5f) / static_cast<float>(count))};
    ch01::Incident in = ch01::incident(point, s.position);
    ch01::Reflected r = ch01::blinn_phong(s.normal, s.to_eye, in.to_light, in.radiance, s.exponent);
    out.diffuse += r.diffuse.x;
    out.specular += r.specular.x;
  }
  return out;
}
// [/points]

// [representative-point]
Terms representative_point_terms(const NeonSurface& s, const NeonLight& light) {
  // Karis 2013. Diffuse: the closed form of the integral of N.L / |L|^2 over the tube with
  // "+ 2" added to the denominator to keep it finite, and the two ends' cosines summed and
  // clamped instead of clipping the tube at the horizon.
  float rho = tube_radius(light);
  glm::vec3 l0 = light.start - s.position, l1 = light.end - s.position;
  float d0 = std::max(glm::length(l0), rho), d1 = std::max(glm::length(l1), rho);
  float cosines = glm::dot(s.normal, l0) / (2.f * d0) + glm::dot(s.normal, l1) / (2.f * d1);
  Terms out;
  out.diffuse = 2.f * saturate(cosines) / (d0 * d1 + glm::dot(l0, l1) + 2.f);
  // Specular: one point light of the whole intensity at the point of the tube closest (in
  // distance) to the reflection ray's line, its lobe widened by alpha / alpha'.
  glm::vec3 R = reflection(s), ld = l1 - l0;
  float r_ld = glm::dot(R, ld), denom = glm::dot(ld, ld) - r_ld * r_ld;
  // The published formula divides by zero when R is parallel to the tube: we take the start.
  float t = denom > 1e-6f * glm::dot(ld, ld) ? (glm::dot(R, l0) * r_ld - glm::dot(l0, ld)) / denom : 0.f;
  glm::vec3 p = l0 + saturate(t) * ld;
  float dist = std::max(glm::length(p), rho);
  float alpha = std::sqrt(2.f / (s.exponent + 2.f));  // chapter 01's roughness mapping, inverted
  float widened = std::min(1.f, alpha + 0.5f * light.length() / (2.f * dist));
  out.specular = specular_lobe(s, p / dist) * (alpha / widened) / (dist * dist);
  return out;
}
// [/representative-point]

// [source-fit]
SourceFit fit_source(float length) {
  // The truth in front of the tube's middle, facing it: E(d) = 1 / (d sqrt(d^2 + L^2 / 4)).
  auto truth = [&](float d) { return 1.f / (d * std::sqrt(d * d + 0.25f * length * length)); };
  float d1 = std::max(0.5f * length, 0.05f), d2 = 4.f * d1;
  // k (1 - d/R)^2 = E at d1 and d2: the ratio gives R, then E(d1) gives k.
  float q = std::sqrt(truth(d1) / truth(d2));
  SourceFit fit;
  fit.radius = (q * d2 - d1) / (q - 1.f);
  fit.scale = truth(d1) / ((1.f - d1 / fit.radius) * (1.f - d1 / fit.radius));
  return fit;
}
// [/source-fit]

// [source]
Terms source_terms(const NeonSurface& s, const NeonLight& light) {
  // The thesis's neon light (its listings 4.11 and 4.12), as written, with its radius and
  // brightness fitted to the truth (fit_source): light.intensity x scale at the tube, 0 at
  // the radius, which is also where the thesis's volume ends.
  float length = light.length();
  glm::vec3 u = length > 0 ? (light.end - light.start) / length : glm::vec3(1, 0, 0);
  SourceFit fit = fit_source(length);
  float radius = fit.radius;
  // Diffuse: the closest point, and the normal bent towards it the more the closer it is.
  glm::vec3 closest = glm::mix(light.start, light.end, closest_on_segment(s.position, light.start, light.end));
  glm::vec3 to_light = closest - s.position;
  float dist = glm::length(to_light);
  if (dist > radius) return {};
  glm::vec3 cp = dist > 0 ? to_light / dist : s.normal;
  float h = saturate(dist / radius);
  glm::vec3 bent = glm::normalize(s.normal + cp * (1.f - h * h) * 0.5f);
  float attenuation = saturate(glm::dot(cp, bent)) * (1.f - h);
  Terms out;
  out.diffuse = fit.scale * attenuation * attenuation;
  // Specular: closest points of the tube's line and the reflection line; the highlight
  // is bright where they nearly meet, and spreads with the distance along the ray.
  glm::vec3 R = reflection(s), start = light.start - s.position;
  float a = glm::dot(u, R), b = glm::dot(u, start), c = glm::dot(R, start);
  float aa = 1.f - a * a;
  bool parallel = aa == 0.f;  // exactly parallel only: the artefacts are its neighbours
  float sc = parallel ? 0.f : (a * c - b) / aa;
  sc = sc > 0 && sc <= length ? sc : sc > length ? length : 0.f;
  glm::vec3 on_tube = light.start + sc * u, to_tube = on_tube - s.position;
  float tc = glm::dot(R, to_tube);
  glm::vec3 on_ray = s.position + tc * R;
  float dot_lr = glm::length(to_tube) > 0 ? saturate(glm::dot(glm::normalize(to_tube), R)) : 0.f;
  float miss = std::max(glm::length(on_tube - on_ray) / radius, 1e-6f);
  float spread = 1.f + tc / radius;
  out.specular = fit.scale * dot_lr * saturate(1.f - std::pow(miss, spread));
  return out;
}
// [/source]

NeonResult neon_light(const NeonSurface& s, const NeonLight& light, Method method, int samples, float radius,
                      float doors) {
  // The truth is not cut (an infinite radius keeps only a cylinder's ends): what every method
  // is measured against includes the light the volume's cut leaves out.
  if (method == Method::GroundTruth) radius = std::numeric_limits<float>::infinity();
  float mask = volume_mask(s.position, light, radius);
  if (mask != 0 && light.barn_doors.enabled()) mask *= barn_doors_mask(s.position, light, doors < 0 ? doors_radius(light) : doors);
  if (mask == 0) return {};
  Terms t;
  switch (method) {
    case Method::GroundTruth: t = ground_truth_terms(s, light, samples); break;
    case Method::Source: t = source_terms(s, light); break;
    case Method::Improved: t = improved_terms(s, light); break;
    case Method::Points: t = points_terms(s, light, samples); break;
    case Method::RepresentativePoint: t = representative_point_terms(s, light); break;
    case Method::AnalyticDiffuse: t = analytic_diffuse_terms(s, light); break;
  }
  glm::vec3 colour = light.color * light.intensity * mask;
  return {colour * t.diffuse, colour * (t.specular * light.specular)};
}

}  // namespace lp::ch04
