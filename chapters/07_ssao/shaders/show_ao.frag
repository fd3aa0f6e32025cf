#version 450
// The AO term itself (--show ao): A as grey, written so that the 8-bit sRGB image holds
// round(255 A) (the output is sRGB-encoded, so the shader writes A decoded from sRGB).
layout(binding = AO_UNIT) uniform sampler2D u_ao;  // the stage's unit (AoStage)
uniform vec2 u_size;  // the output's size
uniform float u_heat; // > 0: a heat map (black 0, blue, green, yellow, red at u_heat), not grey
out vec4 colour;
float srgb_to_linear(float c) { return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4); }
void main() {
  ivec2 size = textureSize(u_ao, 0);
  ivec2 texel = min(ivec2(gl_FragCoord.xy) * size / ivec2(u_size), size - 1);
  float v = texelFetch(u_ao, texel, 0).r;
  if (u_heat > 0.0) {
    float t = clamp(v / u_heat, 0.0, 1.0);
    vec3 c = t < 0.25 ? mix(vec3(0.0), vec3(0.0, 0.0, 1.0), t / 0.25)
           : t < 0.5  ? mix(vec3(0.0, 0.0, 1.0), vec3(0.0, 1.0, 0.0), (t - 0.25) / 0.25)
           : t < 0.75 ? mix(vec3(0.0, 1.0, 0.0), vec3(1.0, 1.0, 0.0), (t - 0.5) / 0.25)
                      : mix(vec3(1.0, 1.0, 0.0), vec3(1.0, 0.0, 0.0), (t - 0.75) / 0.25);
    colour = vec4(c, 1.0);
    return;
  }
  colour = vec4(vec3(srgb_to_linear(clamp(v, 0.0, 1.0))), 1.0);
}
