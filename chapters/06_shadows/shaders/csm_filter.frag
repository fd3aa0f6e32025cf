#version 450
// Convolution shadow maps' pre-filter (csm_math.h [csm]), one direction per pass, a box of
// 2 r + 1 texels: the first pass turns each depth z of the sun's map into the basis values
// sin(c_k z), cos(c_k z), k = 1..u_terms, four to a layer of the target array; the second
// averages the first's layers. The basis is linear in what the lookup reconstructs, so the
// average of the basis is the basis of the average shadow test.
uniform sampler2D u_depth;       // on the stage's own units (ShadowStage::filter_csm)
uniform sampler2DArray u_input;
uniform ivec2 u_step;   // (1, 0) or (0, 1)
uniform int u_radius;
uniform int u_terms;    // 1 .. CSM_MAX_TERMS
uniform bool u_from_depth;
#include "06_shadows/shaders/csm_math.glsl"
layout(location = 0) out vec4 out_layer[CSM_MAX_TERMS / 2];

// Layer l holds terms 2 l + 1 and 2 l + 2 (csm_math.glsl's csm_basis_layer).
vec4 basis_at(ivec2 p, int layer) {
  ivec2 size = textureSize(u_depth, 0).xy;
  p = clamp(p, ivec2(0), size - 1);
  if (!u_from_depth) return texelFetch(u_input, ivec3(p, layer), 0);
  return csm_basis_layer(texelFetch(u_depth, p, 0).r, layer);
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float w = 1.0 / float(2 * u_radius + 1);
  for (int layer = 0; layer < CSM_MAX_TERMS / 2; ++layer) {
    vec4 sum = vec4(0.0);
    if (2 * layer < u_terms)
      for (int i = -u_radius; i <= u_radius; ++i) sum += w * basis_at(p + i * u_step, layer);
    out_layer[layer] = sum;
  }
}
