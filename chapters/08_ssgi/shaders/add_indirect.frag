#version 450
// Added into chapter 03's light buffer (blending one + one) after the direct lights: the
// ambient light the AO leaves, A x ambient, and the indirect light, both diffuse light (L1),
// so the composite multiplies them by the albedo. Nothing is added to the specular light.
layout(binding = GI_UNIT) uniform sampler2D u_gi;  // rgb: L1_ind, a: A (the stage's first unit)
uniform vec3 u_ambient;
uniform int u_gi_on;  // 0: no pass ran (mode off): A = 1, no indirect light
layout(location = 0) out vec4 out_diffuse;
layout(location = 1) out vec4 out_specular;
// [add-indirect]
void main() {
  vec4 gi = u_gi_on != 0 ? texelFetch(u_gi, ivec2(gl_FragCoord.xy), 0) : vec4(0.0, 0.0, 0.0, 1.0);
  out_diffuse = vec4(u_ambient * gi.a + gi.rgb, 0.0);
  out_specular = vec4(0.0);
}
// [/add-indirect]
