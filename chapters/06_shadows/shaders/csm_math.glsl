// Convolution shadow maps' series in GLSL: the twin of csm_math.h (its comments derive it),
// included by the pre-filter (csm_filter.frag) and the lookup (shadow_visibility.glsl), and held
// to the C++ by 06_shadows.gl.GlslTwins.CsmBasisAndReconstructionMatchTheirCppTwins. Layer l of
// the map holds terms 2 l + 1 and 2 l + 2, (sin, cos) of each.
#define CSM_MAX_TERMS 8
float csm_coefficient(int k) { return float(2 * k - 1) * 3.14159265358979; }  // c_k, k from 1

// [csm-basis-glsl]
// The stored values of depth z for layer l: sin(c z), cos(c z) of its two terms.
vec4 csm_basis_layer(float z, int layer) {
  float c1 = csm_coefficient(2 * layer + 1), c2 = csm_coefficient(2 * layer + 2);
  return vec4(sin(c1 * z), cos(c1 * z), sin(c2 * z), cos(c2 * z));
}
// [/csm-basis-glsl]

// [csm-glsl]
// csm_math.h's csm_visibility: the step's series from the filtered sin(c_k z), cos(c_k z) and
// the receiver's depth, sin(c (z - d)) = sin(c z) cos(c d) - cos(c z) sin(c d); doubled and
// clamped, so that a receiver on its own occluder (the series' 1/2) reads lit.
float csm_visibility(vec4 layers[CSM_MAX_TERMS / 2], float d, int terms) {
  float sum = 0.5;
  for (int k = 1; k <= terms; ++k) {
    vec2 b = (k & 1) == 1 ? layers[(k - 1) / 2].xy : layers[(k - 1) / 2].zw;
    float c = csm_coefficient(k);
    sum += 2.0 * (b.x * cos(c * d) - b.y * sin(c * d)) / c;
  }
  return clamp(2.0 * sum, 0.0, 1.0);
}
// [/csm-glsl]
