#version 450
// The stencil pass writes no colour: only the stencil operations do anything. An empty
// fragment shader is the cheapest one there is.
#ifdef COUNT_FRAGMENTS
// Counting (tests, the panel, --bench): the fragments of the marking draws that pass the
// depth and stencil tests. GL_SAMPLES_PASSED counts them too, although they shade nothing;
// with early tests, as in light.frag, this shader runs for exactly those, so the pass's
// GL_SAMPLES_PASSED is light.frag's shaded count plus this one.
layout(early_fragment_tests) in;
#include "03_light_volumes/shaders/fragment_counters.glsl"
const uint kCountMarking = 3u;
#endif

void main() {
#ifdef COUNT_FRAGMENTS
  count_fragment(kCountMarking);
#endif
}
