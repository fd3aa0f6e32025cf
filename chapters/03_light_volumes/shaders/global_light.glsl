// The lights that reach every pixel, ambient and the directional lights: the global pass's
// body, shared by its two drivers so that they cannot drift. global.frag runs it for each
// fragment of a full-screen triangle and writes the light buffer through the framebuffer;
// global.comp runs it for each invocation of a compute pass and writes the light buffer as
// images. Both write every pixel, so nothing is cleared first.
#include "01_forward/shaders/lighting.glsl"
#include "02_gbuffer/shaders/gbuffer.glsl"
#include FRAME_VISIBILITY  // hooks/full_visibility.glsl, or a later chapter's (shadows)
#include FRAME_AMBIENT     // hooks/constant_ambient.glsl, or a later chapter's (AO, indirect)

layout(std430, binding = 0) readonly buffer Lights { GpuLight lights[]; };

uniform vec3 u_ambient;
uniform int u_light_count;

// L1 (diffuse light) and L2 (specular light, times the surface's specular colour) at `pixel`;
// deferred lighting's one target instead (LIGHT_PREPASS): diffuse, and the specular light's
// luminance in alpha, l2 unused.
void global_light(ivec2 pixel, out vec4 l1, out vec4 l2) {
  Surface s = decode_gbuffer(pixel);
  vec3 diffuse = vec3(0.0), specular = vec3(0.0);
  if (!s.is_sky) {
    vec3 to_eye = normalize(gb_eye.xyz - s.position);
    for (int i = 0; i < u_light_count; ++i) {
      vec3 to_light, radiance;
      light_incident(lights[i], s.position, to_light, radiance);
      radiance *= directional_visibility(i, lights[i], s);
      blinn_phong(s.normal, to_eye, to_light, radiance, s.exponent, diffuse, specular);
    }
    diffuse += ambient_light(u_ambient, s, pixel);  // the thesis starts L1 with the ambient light
  }
#ifdef LIGHT_PREPASS
  l1 = vec4(diffuse, dot(specular, vec3(0.2126, 0.7152, 0.0722)));
  l2 = vec4(0.0);
#else
  l1 = vec4(diffuse, 0.0);
  l2 = vec4(s.specular * specular, 0.0);
#endif
}
