#version 450
// Shows one quantity of the G-buffer. Colours are written as they are (linear, the target
// encodes sRGB); the other views are display values v, written as srgb_to_linear(v) so that
// the PNG holds v * 255.
#include "02_gbuffer/shaders/gbuffer.glsl"

uniform int u_view;  // BufferView in deferred.h
uniform vec3 u_background;
out vec4 out_color;

const int VIEW_ALBEDO = 0, VIEW_NORMAL = 1, VIEW_DEPTH = 2, VIEW_SPECULAR = 3, VIEW_EXPONENT = 4,
          VIEW_EMISSIVE = 5, VIEW_POSITION = 6;

vec3 display(vec3 v) {  // the inverse of the sRGB encoding the target applies
  v = clamp(v, 0.0, 1.0);
  return mix(v / 12.92, pow((v + 0.055) / 1.055, vec3(2.4)), greaterThan(v, vec3(0.04045)));
}

void main() {
  Surface s = decode_gbuffer(ivec2(gl_FragCoord.xy));
  if (s.is_sky) {
    out_color = vec4(u_background, 1.0);
    return;
  }
  vec3 c;
  // [view-values]
  if (u_view == VIEW_ALBEDO) c = s.albedo;
  else if (u_view == VIEW_SPECULAR) c = s.specular;
  else if (u_view == VIEW_EMISSIVE) c = s.emissive;
  else if (u_view == VIEW_NORMAL) c = display(s.normal * 0.5 + 0.5);
  else if (u_view == VIEW_EXPONENT) c = display(vec3(log2(s.exponent) / GB_MAX_LOG2_EXPONENT));
  else if (u_view == VIEW_DEPTH) {
    float near = gb_depth_info.x, far = gb_depth_info.y;
    float distance = length(s.position - gb_eye.xyz);  // from the stored depth, reconstructed
    c = display(vec3(log(distance / near) / log(far / near)));
  } else {  // VIEW_POSITION: each world coordinate as a smooth ramp with a 2 m period, so
           // that the reconstructed point shows as bands of colour (smooth: renderers
           // that differ in the last bit of the position differ in the last bit here too)
    c = display(0.5 + 0.3 * cos(3.14159265 * s.position));
  }
  // [/view-values]
  out_color = vec4(c, 1.0);
}
