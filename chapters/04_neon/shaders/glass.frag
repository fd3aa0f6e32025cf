#version 450
// The glowing glass of a tube. Its true radiance, (I / L) / (2 radius), is far above what
// an 8-bit image holds (chapter 05 brings HDR), so it is drawn at its colour's full
// saturation: the brightest hue the output can show.
layout(early_fragment_tests) in;

flat in vec3 v_power;
in vec3 v_position;

out vec4 out_color;

void main() {
  float brightest = max(max(v_power.r, v_power.g), max(v_power.b, 1e-6));
  out_color = vec4(v_power / brightest, 1.0);
}
