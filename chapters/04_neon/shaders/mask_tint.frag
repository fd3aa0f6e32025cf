#version 450
// A picture of a tube's stencil mask: its light pass adds a third of the tube's colour (at
// full saturation, as the glass) instead of its light.
layout(early_fragment_tests) in;

flat in vec3 v_power;

out vec4 out_color;

void main() {
  float brightest = max(max(v_power.r, v_power.g), max(v_power.b, 1e-6));
  out_color = vec4(0.3 * v_power / brightest, 1.0);
}
