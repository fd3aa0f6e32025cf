#version 450
// Shows a count per pixel (fragments shaded, or lit) as a colour ramp: black 0, then blue,
// green, yellow, red, white at u_full_scale and beyond.
layout(binding = 5) uniform sampler2D u_count;
uniform float u_full_scale;
out vec4 out_color;

vec3 ramp(float t) {
  const vec3 stops[6] = vec3[](vec3(0.0), vec3(0.0, 0.1, 0.6), vec3(0.0, 0.6, 0.3), vec3(0.9, 0.8, 0.0),
                               vec3(0.9, 0.1, 0.0), vec3(1.0));
  float x = clamp(t, 0.0, 1.0) * 5.0;
  int i = min(int(x), 4);
  return mix(stops[i], stops[i + 1], x - float(i));
}

// The ramp's colours are display values: undo the sRGB encoding the target will apply.
vec3 display(vec3 v) { return mix(v / 12.92, pow((v + 0.055) / 1.055, vec3(2.4)), greaterThan(v, vec3(0.04045))); }

void main() {
  float n = texelFetch(u_count, ivec2(gl_FragCoord.xy), 0).r;
  out_color = vec4(display(n > 0.0 ? ramp(n / u_full_scale) : vec3(0.0)), 1.0);
}
