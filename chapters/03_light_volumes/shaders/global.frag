#version 450
// The lights that reach every pixel: ambient and the directional lights, one full-screen
// pass that also starts the light buffer (it writes every pixel, so nothing is cleared).
#include "01_forward/shaders/lighting.glsl"
#include "02_gbuffer/shaders/gbuffer.glsl"
#include FRAME_VISIBILITY  // hooks/full_visibility.glsl, or a later chapter's (shadows)
#include FRAME_AMBIENT     // hooks/constant_ambient.glsl, or a later chapter's (AO, indirect)

layout(early_fragment_tests) in;
layout(std430, binding = 0) readonly buffer Lights { GpuLight lights[]; };

uniform vec3 u_ambient;
uniform int u_light_count;

layout(location = 0) out vec4 out_diffuse;
layout(location = 1) out vec4 out_specular;

void main() {
  Surface s = decode_gbuffer(ivec2(gl_FragCoord.xy));
  vec3 diffuse = vec3(0.0), specular = vec3(0.0);
  if (!s.is_sky) {
    vec3 to_eye = normalize(gb_eye.xyz - s.position);
    for (int i = 0; i < u_light_count; ++i) {
      vec3 to_light, radiance;
      light_incident(lights[i], s.position, to_light, radiance);
      radiance *= directional_visibility(i, lights[i], s);
      blinn_phong(s.normal, to_eye, to_light, radiance, s.exponent, diffuse, specular);
    }
    diffuse += ambient_light(u_ambient, s, ivec2(gl_FragCoord.xy));  // the thesis starts L1 with the ambient light
  }
#ifdef LIGHT_PREPASS
  out_diffuse = vec4(diffuse, dot(specular, vec3(0.2126, 0.7152, 0.0722)));
#else
  out_diffuse = vec4(diffuse, 0.0);
  out_specular = vec4(s.specular * specular, 0.0);
#endif
}
