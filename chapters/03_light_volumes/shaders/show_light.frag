#version 450
// Shows one target of the light buffer: the light it holds, scaled, as a colour.
layout(binding = 5) uniform sampler2D u_light;
uniform float u_scale;
out vec4 out_color;
void main() { out_color = vec4(texelFetch(u_light, ivec2(gl_FragCoord.xy), 0).rgb * u_scale, 1.0); }
