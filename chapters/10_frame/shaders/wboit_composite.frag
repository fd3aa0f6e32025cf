#version 450
// Chapter 10: WBOIT's composite. Over the image, the weighted average of the glass colours
// covering (1 - revealage) of it: C = (sum w alpha c / sum w alpha) (1 - r) + C_image r,
// with the output blended ONE, ONE_MINUS_SRC_ALPHA (premultiplied). Or one of the two targets shown.
// WBOIT_SAMPLES: the targets are multisampled (chapter 10's MSAA): the pass runs once per
// sample (it reads gl_SampleID), each sample's glass over that sample of the image.
#ifdef WBOIT_SAMPLES
layout(binding = 0) uniform sampler2DMS u_accumulation;
layout(binding = 1) uniform sampler2DMS u_revealage;
#define WBOIT_SAMPLE gl_SampleID
#else
layout(binding = 0) uniform sampler2D u_accumulation;  // RGBA16F: sum of w (alpha c, alpha)
layout(binding = 1) uniform sampler2D u_revealage;     // R16F: product of (1 - alpha)
#define WBOIT_SAMPLE 0
#endif
uniform int u_show;  // 0 the image, 1 the accumulation's average colour, 2 the revealage

out vec4 out_color;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 sum = texelFetch(u_accumulation, p, WBOIT_SAMPLE);
  float revealage = texelFetch(u_revealage, p, WBOIT_SAMPLE).r;
  // [wboit-composite]
  // A half float holds at most 65504: many near layers can overflow the sum to infinity.
  // min() keeps it finite (infinity / infinity would be NaN); the clamp is the paper's.
  vec3 average = min(sum.rgb, vec3(65504.0)) / clamp(sum.a, 1e-4, 5e4);
  // [/wboit-composite]
  if (u_show == 1) { out_color = vec4(average, 1.0); return; }
  if (u_show == 2) { out_color = vec4(vec3(revealage), 1.0); return; }
  if (revealage >= 1.0) discard;  // no glass here: the image untouched
  // Premultiplied, blended ONE, ONE_MINUS_SRC_ALPHA: an 8-bit target clamps what the shader
  // writes to [0, 1], so a highlight brighter than 1 keeps its coverage's worth of light.
  out_color = vec4(average * (1.0 - revealage), 1.0 - revealage);
}
