#version 450
// Drawn where the stencil count is not 0: in shadow.
layout(location = 0) out vec4 out_value;
void main() { out_value = vec4(0.0); }
