#version 450
// The AO term itself (--show ao): A as grey, written so that the 8-bit sRGB image holds
// round(255 A) (the output is sRGB-encoded, so the shader writes A decoded from sRGB).
layout(binding = 8) uniform sampler2D u_ao;
uniform vec2 u_size;  // the output's size
out vec4 colour;
float srgb_to_linear(float c) { return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4); }
void main() {
  ivec2 size = textureSize(u_ao, 0);
  ivec2 texel = min(ivec2(gl_FragCoord.xy) * size / ivec2(u_size), size - 1);
  colour = vec4(vec3(srgb_to_linear(clamp(texelFetch(u_ao, texel, 0).r, 0.0, 1.0))), 1.0);
}
