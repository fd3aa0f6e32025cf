// The light leaving one surface sample towards the eye, every light of the frame summed in
// one shader: chapter 03's global pass (ambient and the directional lights), each local light
// with chapter 03's cut (local_light.glsl), and chapter 03's composite
// F = albedo * L1 + L2 + emissive. The per-pixel and the per-sample passes both call it, so
// the two rates light with the same code. With MsaaLights::Volumes the local lights are
// chapter 03's volumes instead (msaa_volume.frag) and u_local_count is 0 here.
#include "10_frame/shaders/msaa_surface.glsl"
#include FRAME_AMBIENT     // chapter 03's hooks/constant_ambient.glsl

// struct LocalLight, shared with msaa.cpp
#include "10_frame/shaders/msaa_local_light.h"
layout(std430, binding = 0) readonly buffer Directional { GpuLight directional[]; };
layout(std430, binding = 1) readonly buffer Locals { LocalLight locals[]; };
uniform int u_directional_count, u_local_count;
uniform vec3 u_ambient, u_background;

// [frame-radiance]
vec3 frame_radiance(Surface s, ivec2 pixel) {
  if (s.is_sky) return u_background;
  vec3 diffuse = vec3(0.0), specular = vec3(0.0);
  vec3 to_eye = normalize(gb_eye.xyz - s.position);
  for (int i = 0; i < u_directional_count; ++i) {  // chapter 03's global pass
    vec3 to_light, radiance;
    light_incident(directional[i], s.position, to_light, radiance);
    radiance *= directional_visibility(i, directional[i], s);
    blinn_phong(s.normal, to_eye, to_light, radiance, s.exponent, diffuse, specular);
  }
  diffuse += ambient_light(u_ambient, s, pixel);
  for (int i = 0; i < u_local_count; ++i) {  // chapter 03's volumes, as a loop (or 0: volumes)
    vec3 d, sp;
    local_light(locals[i].light, locals[i].cut.x, i, s, d, sp);
    diffuse += d;
    specular += sp;
  }
  return s.albedo * diffuse + s.specular * specular + s.emissive;  // chapter 03's composite
}
// [/frame-radiance]
