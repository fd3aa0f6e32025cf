#version 450
// The sun's visibility term alone, grey (1 lit, 0 shadow); the sky and surfaces facing away
// from the sun in the background colour's place: blue, so a picture never mistakes them.
#include "01_forward/shaders/lighting.glsl"
#include "02_gbuffer/shaders/gbuffer.glsl"
#include FRAME_VISIBILITY
uniform vec3 u_sun_direction;  // the way the sun shines
uniform vec2 u_output_size;
uniform vec3 u_spot_direction;  // SHOW_SPOT: the marked spot light's axis and cos(outer cone)
uniform float u_spot_cos_cone;
layout(location = 0) out vec4 out_colour;
void main() {
#ifdef SHOW_MAP
  // The sun's depth map itself, as large a square as fits, centred; near black, far white.
  float side = min(u_output_size.x, u_output_size.y);
  vec2 uv = (gl_FragCoord.xy - 0.5 * (u_output_size - side)) / side;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) { out_colour = vec4(0.1, 0.15, 0.4, 1.0); return; }
  out_colour = vec4(vec3(texture(sh_depth, uv).r), 1.0);
  return;
#endif
  Surface s = decode_gbuffer(ivec2(gl_FragCoord.xy));
#ifdef SHOW_SPOT
  // The marked spot light's visibility alone; blue where it does not reach (outside its cone,
  // facing away, the sky).
  vec3 from_spot = normalize(s.position - sh.spot_position);
  if (s.is_sky || dot(s.normal, -from_spot) <= 0.0 || dot(from_spot, u_spot_direction) < u_spot_cos_cone) {
    out_colour = vec4(0.1, 0.15, 0.4, 1.0);
    return;
  }
  GpuLight spot = GpuLight(vec4(sh.spot_position, LIGHT_SPOT), vec4(u_spot_direction, 0.0), vec4(1.0), vec4(0.0));
  out_colour = vec4(vec3(local_visibility(0, spot, s)), 1.0);
  return;
#endif
  GpuLight sun = GpuLight(vec4(0.0), vec4(u_sun_direction, 0.0), vec4(1.0), vec4(0.0));
  if (s.is_sky || dot(s.normal, -u_sun_direction) <= 0.0) { out_colour = vec4(0.1, 0.15, 0.4, 1.0); return; }
  float v = directional_visibility(0, sun, s);
#ifdef SHOW_PENUMBRA
  out_colour = vec4(vec3(sh_pcss_radius), 1.0);  // PCSS's filter radius, metres (a float target reads it)
  return;
#endif
  out_colour = vec4(vec3(v), 1.0);
}
