#version 450
// The sun's visibility term alone, grey (1 lit, 0 shadow); the sky and surfaces facing away
// from the sun in the background colour's place: blue, so a picture never mistakes them.
#include "01_forward/shaders/lighting.glsl"
#include "02_gbuffer/shaders/gbuffer.glsl"
#include FRAME_VISIBILITY
uniform vec3 u_sun_direction;  // the way the sun shines
uniform vec2 u_output_size;
uniform vec3 u_spot_position;   // SHOW_SPOT: the spot light's position, axis and cos(outer cone)
uniform vec3 u_spot_direction;
uniform float u_spot_cos_cone;
uniform vec3 u_point_position;  // SHOW_POINT: the point light's position and range (0: unbounded)
uniform float u_point_range;
layout(location = 0) out vec4 out_colour;
void main() {
#ifdef SHOW_MAP
  // The sun's depth map itself, as large a square as fits, centred; near black, far white.
  float side = min(u_output_size.x, u_output_size.y);
  vec2 uv = (gl_FragCoord.xy - 0.5 * (u_output_size - side)) / side;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) { out_colour = vec4(0.1, 0.15, 0.4, 1.0); return; }
#if SHADOW_CASCADES > 1
  // The cascades side by side, the nearest on the left, each squeezed into its strip.
  float layer = min(floor(uv.x * float(SHADOW_CASCADES)), float(SHADOW_CASCADES - 1));
  out_colour = vec4(vec3(texture(sh_cascades, vec3(fract(uv.x * float(SHADOW_CASCADES)), uv.y, layer)).r), 1.0);
#else
  out_colour = vec4(vec3(texture(sh_depth, uv).r), 1.0);
#endif
  return;
#endif
  Surface s = decode_gbuffer(ivec2(gl_FragCoord.xy));
#ifdef SHOW_POINT
  // One point light's visibility alone; blue where it does not reach (facing away, beyond its
  // range, the sky).
  vec3 to_point = u_point_position - s.position;
  if (s.is_sky || dot(s.normal, to_point) <= 0.0 || (u_point_range > 0.0 && length(to_point) > u_point_range)) {
    out_colour = vec4(0.1, 0.15, 0.4, 1.0);
    return;
  }
  GpuLight point = GpuLight(vec4(u_point_position, LIGHT_POINT), vec4(0.0), vec4(1.0), vec4(0.0));
  out_colour = vec4(vec3(local_visibility(0, point, s)), 1.0);
  return;
#endif
#ifdef SHOW_SPOT
  // One spot light's visibility alone; blue where it does not reach (outside its cone, facing
  // away, the sky).
  vec3 from_spot = normalize(s.position - u_spot_position);
  if (s.is_sky || dot(s.normal, -from_spot) <= 0.0 || dot(from_spot, u_spot_direction) < u_spot_cos_cone) {
    out_colour = vec4(0.1, 0.15, 0.4, 1.0);
    return;
  }
  GpuLight spot = GpuLight(vec4(u_spot_position, LIGHT_SPOT), vec4(u_spot_direction, 0.0), vec4(1.0), vec4(0.0));
  out_colour = vec4(vec3(local_visibility(0, spot, s)), 1.0);
  return;
#endif
  GpuLight sun = GpuLight(vec4(0.0), vec4(u_sun_direction, 0.0), vec4(1.0), vec4(0.0));
  if (s.is_sky || dot(s.normal, -u_sun_direction) <= 0.0) { out_colour = vec4(0.1, 0.15, 0.4, 1.0); return; }
  float v = directional_visibility(0, sun, s);
#ifdef SHOW_CASCADES
  // The visibility tinted by the cascade the pixel reads (mixed in a blend band), grey beyond
  // the last one.
  const vec3 tints[4] = vec3[4](vec3(1.0, 0.3, 0.3), vec3(0.3, 1.0, 0.3), vec3(0.35, 0.45, 1.0), vec3(1.0, 0.9, 0.2));
  vec3 tint = vec3(0.5);
  if (sh_cascade_shown >= 0.0) {
    int i = int(sh_cascade_shown);
    tint = mix(tints[i], tints[min(i + 1, 3)], fract(sh_cascade_shown));
  }
  out_colour = vec4(tint * (0.3 + 0.7 * v), 1.0);
  return;
#endif
#ifdef SHOW_PENUMBRA
  out_colour = vec4(vec3(sh_pcss_radius), 1.0);  // PCSS's filter radius, metres (a float target reads it)
  return;
#endif
  out_colour = vec4(vec3(v), 1.0);
}
