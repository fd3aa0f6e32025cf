#version 450
// Writes every field of decode_gbuffer() to float targets, for measurements (probe.h).
#include "02_gbuffer/shaders/gbuffer.glsl"

layout(location = 0) out vec4 out_position;  // w: 1 for sky
layout(location = 1) out vec4 out_normal;    // w: exponent
layout(location = 2) out vec4 out_albedo;
layout(location = 3) out vec4 out_specular;
layout(location = 4) out vec4 out_emissive;

void main() {
  Surface s = decode_gbuffer(ivec2(gl_FragCoord.xy));
  out_position = vec4(s.position, s.is_sky ? 1.0 : 0.0);
  out_normal = vec4(s.normal, s.exponent);
  out_albedo = vec4(s.albedo, 0.0);
  out_specular = vec4(s.specular, 0.0);
  out_emissive = vec4(s.emissive, 0.0);
}
