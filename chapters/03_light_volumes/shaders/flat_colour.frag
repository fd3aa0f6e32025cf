#version 450
// The wireframe and the stencil-mask overlay: the light's colour, normalised to its
// brightest channel so that dim lights are as visible as bright ones.
flat in vec4 v_radiance;
uniform float u_alpha;
out vec4 out_color;
void main() {
  vec3 c = v_radiance.rgb / max(max(v_radiance.r, max(v_radiance.g, v_radiance.b)), 1e-6);
  out_color = vec4(c, u_alpha);
}
