#version 450
// The lighting pass of deferred shading: for every pixel, the surface from the G-buffer and
// chapter 01's Blinn-Phong for each light. Same formulas, same order as forward.frag, so the
// two images differ only by what the G-buffer's formats lose.
#include "01_forward/shaders/lighting.glsl"
#include "02_gbuffer/shaders/gbuffer.glsl"

layout(early_fragment_tests) in;

layout(std430, binding = 0) readonly buffer Lights { GpuLight lights[]; };

uniform vec3 u_ambient;
uniform vec3 u_background;
uniform int u_light_count;
uniform bool u_directional_only;

out vec4 out_color;

void main() {
  // [deferred-shade]
  Surface s = decode_gbuffer(ivec2(gl_FragCoord.xy));
  if (s.is_sky) {  // nothing was drawn here: no surface to light
    out_color = vec4(u_background, 1.0);
    return;
  }
  vec3 to_eye = normalize(gb_eye.xyz - s.position);
  vec3 diffuse = vec3(0.0), specular = vec3(0.0);
  for (int i = 0; i < u_light_count; ++i) {
    if (u_directional_only && lights[i].position_type.w != LIGHT_DIRECTIONAL) continue;
    vec3 to_light, radiance;
    light_incident(lights[i], s.position, to_light, radiance);
    blinn_phong(s.normal, to_eye, to_light, radiance, s.exponent, diffuse, specular);
  }
  vec3 color = s.albedo * diffuse + s.specular * specular;
  color += s.albedo * u_ambient + s.emissive;
  out_color = vec4(color, 1.0);
  // [/deferred-shade]
}
