// What chapter 08's stage adds into the light buffer's L1 after the direct lights: the ambient
// light the AO leaves, A x ambient, and the indirect light, both diffuse light, so the composite
// multiplies them by the albedo; nothing goes to the specular light. add_indirect.frag adds it
// by blending one plus one, add_indirect.comp by reading and writing L1 as an image.
layout(binding = GI_UNIT) uniform sampler2D u_gi;  // rgb: L1_ind, a: A (the stage's first unit)
uniform vec3 u_ambient;
uniform int u_gi_on;  // 0: no pass ran (mode off): A = 1, no indirect light

// [add-indirect]
vec3 indirect_diffuse(ivec2 pixel) {
  vec4 gi = u_gi_on != 0 ? texelFetch(u_gi, pixel, 0) : vec4(0.0, 0.0, 0.0, 1.0);
  return u_ambient * gi.a + gi.rgb;
}
// [/add-indirect]
