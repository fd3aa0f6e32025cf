#version 450
// The edges picture: where the stencil is 1, the light replaced by red (early fragment tests).
layout(early_fragment_tests) in;
out vec4 out_radiance;
void main() { out_radiance = vec4(1e4, 0.0, 0.0, 1.0); }
