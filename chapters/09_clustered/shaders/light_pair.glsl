// One pair (surface, light) of chapter 09's shading: chapter 03's local_light() with what it
// computes per light precomputed (cluster_light.h), the distance taken once and one division:
// the same formulas (chapter 01's light_incident, distance_attenuation, spot_cone and
// blinn_phong), rounded differently (GlslTwins.LightPairMatchesItsCppTwin bounds it). Needs
// 01_forward/shaders/lighting.glsl, 02_gbuffer/shaders/gbuffer.glsl and FRAME_VISIBILITY first.
// `to_eye` is the surface's, normalised once per pixel.
#include "09_clustered/shaders/cluster_light.h"
// [light-pair]
void light_pair(ClusterLight c, bool spot, vec4 cone, int index, Surface s, vec3 to_eye, inout vec3 diffuse,
                inout vec3 specular, inout uint lit) {
  vec3 d = c.position_radius.xyz - s.position;
  float distance = length(d);  // local_light's test: the light ends at its cut
  if (!(distance <= c.position_radius.w)) return;
  float inv = 1.0 / distance;  // the pair's one division (infinite on the light: guarded below)
  vec3 to_light = distance > 0.0 ? d * inv : vec3(0.0, 1.0, 0.0);
  float d2 = distance * distance;
  float x = d2 * c.radiance_inv_range2.w;  // (distance / range)^2
  float window = clamp(1.0 - x * x, 0.0, 1.0);
  float a = window * window * min(inv * inv, 1e4);  // 1 / max(distance^2, 1e-4)
  if (spot) {
    float t = clamp(dot(-to_light, cone.xyz) + cone.w, 0.0, 1.0);
    a *= t * t;
  }
  // The visibility hook reads where the light is and its kind (chapter 06's maps find theirs so).
  GpuLight hook = GpuLight(vec4(c.position_radius.xyz, spot ? LIGHT_SPOT : LIGHT_POINT), vec4(0.0),
                           vec4(c.radiance_inv_range2.rgb, 0.0), vec4(0.0));
  vec3 radiance = c.radiance_inv_range2.rgb * a * local_visibility(index, hook, s);
  vec3 df = vec3(0.0), sp = vec3(0.0);
  blinn_phong(s.normal, to_eye, to_light, radiance, s.exponent, df, sp);
  diffuse += df;
  specular += s.specular * sp;
  if (any(greaterThan(df + sp, vec3(0.0)))) ++lit;
}
// [/light-pair]
