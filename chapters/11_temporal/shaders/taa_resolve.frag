#version 450
// Temporal anti-aliasing, one pixel: this frame's jittered sample blended into the history
// moved by the motion vectors, the history read with a Catmull-Rom filter, clipped to this
// frame's 3x3 neighbourhood in YCoCg, and dropped where the surface was hidden last frame.
layout(binding = 0) uniform sampler2D u_current;          // this frame's radiance (jittered)
layout(binding = 1) uniform sampler2D u_history;          // the last result (bilinear sampler)

uniform float u_alpha;
uniform int u_filter;  // 0 bilinear, 1 Catmull-Rom
uniform int u_clip;    // 0 off, 1 clamp in RGB, 2 clip in YCoCg
uniform int u_reject_disocclusion;
uniform int u_tonemapped;
uniform int u_has_exposure;
// Chapter 05's eye (its ExposureState): the exposure the last frame was tonemapped with.
layout(std430, binding = 0) readonly buffer Eye { float eye_target, eye_adapted, eye_exposure, eye_mean_log, eye_count; };
uniform int u_reset;
uniform vec2 u_jitter;         // this frame's offset in pixels (x right, y up)
uniform int u_unjitter;        // this frame's pixel rebuilt at its centre from the 3x3's samples
uniform float u_gamma;         // > 0: the box is the neighbourhood's mean +- gamma sigma (within its extremes)
uniform float u_alpha_moving;  // this frame's weight where the surface moved a pixel or more
// The remembered box (the clip's space): this frame's, widened by the last frames' boxes; each
// frame keeps u_box_keep of the widening (0: this frame's box alone).
layout(binding = 4) uniform sampler2D u_box_lo;
layout(binding = 5) uniform sampler2D u_box_hi;
uniform float u_box_keep;

layout(location = 0) out vec4 out_color;
layout(location = 1) out float out_rejected;
layout(location = 2) out vec4 out_box_lo;
layout(location = 3) out vec4 out_box_hi;

// [resolve-space]
// The blend runs on exposed colour compressed by c / (1 + luminance): a bright sample then
// weighs no more than a tonemapped pixel would, so one firefly cannot smear over frames.
float luma(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }
float exposure() { return u_has_exposure != 0 && eye_exposure > 0.0 ? eye_exposure : 1.0; }
vec3 to_space(vec3 c) {
  c = max(c, vec3(0.0));
  if (u_tonemapped == 0) return c;
  c *= exposure();
  return c / (1.0 + luma(c));
}
vec3 from_space(vec3 t) {
  if (u_tonemapped == 0) return t;
  return t / (max(1.0 - luma(t), 1e-7) * exposure());
}
vec3 rgb_to_ycocg(vec3 c) {
  return vec3(0.25 * c.r + 0.5 * c.g + 0.25 * c.b, 0.5 * c.r - 0.5 * c.b, -0.25 * c.r + 0.5 * c.g - 0.25 * c.b);
}
vec3 ycocg_to_rgb(vec3 y) {
  float t = y.x - y.z;
  return vec3(t + y.y, y.x + y.z, t - y.y);
}
// [/resolve-space]

#include "11_temporal/shaders/catmull_rom.glsl"

// With --exercise 2 the reader's clip_to_box (chapters/11_temporal/exercises/) stands in.
#ifdef EXERCISE_CLIP_TO_BOX
#include EXERCISE_CLIP_TO_BOX
#else
// [clip-box]
// Moves q towards the box's centre until it lies inside (Playdead's clip; a clamp per axis
// would also move its hue).
vec3 clip_to_box(vec3 lo, vec3 hi, vec3 q) {
  vec3 c = 0.5 * (hi + lo), e = 0.5 * (hi - lo);
  vec3 v = q - c;
  vec3 a = abs(v / e);
  float m = max(a.x, max(a.y, a.z));
  return m > 1.0 ? c + v / m : q;
}
// [/clip-box]
#endif

#include "11_temporal/shaders/disocclusion.glsl"

void main() {
  ivec2 size = textureSize(u_current, 0);
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec2 uv = (vec2(p) + 0.5) / vec2(size);
  vec4 here = texelFetch(u_current, p, 0);
  vec3 centre = to_space(here.rgb);
  // [neighbourhood]
  // This frame's 3x3: the box the history must fall in, and the nearest surface, whose
  // motion an edge pixel takes (the edge moves with the object in front).
  vec3 lo = vec3(1e30), hi = vec3(-1e30), m1 = vec3(0.0), m2 = vec3(0.0), filtered = vec3(0.0);
  float weights = 0.0;
  float nearest = 1e30;
  ivec2 nearest_p = p;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 q = clamp(p + ivec2(dx, dy), ivec2(0), size - 1);
      vec3 c = to_space(texelFetch(u_current, q, 0).rgb);
      vec3 y = u_clip == 2 ? rgb_to_ycocg(c) : c;
      lo = min(lo, y);
      hi = max(hi, y);
      m1 += y;
      m2 += y * y;
      // q's sample lies at q's centre less the jitter; a Gaussian fit of Blackman-Harris
      // (Karis 2014) weighs it by its distance from p's centre.
      vec2 off = vec2(dx, dy) - u_jitter;
      float wq = exp(-2.29 * dot(off, off));
      filtered += wq * c;
      weights += wq;
      float d = texelFetch(u_motion, q, 0).w;
      if (d < nearest) { nearest = d; nearest_p = q; }
    }
  // [/neighbourhood]
  // [variance-clip]
  // Variance clipping (Salvi 2016): the box mean +- gamma sigma within the extremes, which one
  // outlier widens. It always holds this frame's pixel: at an edge that can lie beyond one
  // sigma, and a history equal to it must not be pulled towards the mean.
  if (u_gamma > 0.0) {
    vec3 mu = m1 / 9.0, sigma = sqrt(max(m2 / 9.0 - mu * mu, vec3(0.0)));
    vec3 own_y = u_clip == 2 ? rgb_to_ycocg(centre) : centre;
    lo = min(max(lo, mu - u_gamma * sigma), own_y);
    hi = max(min(hi, mu + u_gamma * sigma), own_y);
  }
  // [/variance-clip]
  if (u_unjitter != 0) centre = filtered / weights;
  // [reproject]
  vec4 own = texelFetch(u_motion, p, 0);
  vec2 uv_then = uv - texelFetch(u_motion, nearest_p, 0).xy;
  bool rejected = u_reset != 0 || any(lessThan(uv_then, vec2(0.0))) || any(greaterThan(uv_then, vec2(1.0)));
  if (!rejected && u_reject_disocclusion != 0) rejected = disoccluded(uv - own.xy, own.z, depth_slack(p, size, own.z));
  float moved = length(texelFetch(u_motion, nearest_p, 0).xy * vec2(size));
  // [/reproject]
  // [box-memory]
  // A feature thinner than a pixel is missed by the jitter in some frames: then this frame's
  // 3x3 holds none of it, and a clip to that box alone erases it from the history. Where the
  // surface is still, the box also holds what the last frames' boxes held around this point,
  // each frame keeping u_box_keep of that widening (what a light that changed left behind
  // fades within a few frames). The memory spans about 1 / (1 - u_box_keep) frames: it is this
  // pixel's only while the surface moves less than a pixel in that time, and fades out as it
  // moves more.
  vec3 own_lo = lo, own_hi = hi;
  if (!rejected && u_box_keep > 0.0) {
    ivec2 t = clamp(ivec2(uv_then * vec2(size)), ivec2(0), size - 1);  // the texel the point was in
    float still = 1.0 - clamp(moved / (1.0 - u_box_keep), 0.0, 1.0);
    lo = min(lo, mix(lo, texelFetch(u_box_lo, t, 0).xyz, still));
    hi = max(hi, mix(hi, texelFetch(u_box_hi, t, 0).xyz, still));
  }
  out_box_lo = vec4(mix(own_lo, lo, u_box_keep), 0.0);
  out_box_hi = vec4(mix(own_hi, hi, u_box_keep), 0.0);
  // [/box-memory]
  // The history is stored in half floats (a relative step of 2^-11): a box narrower than twice
  // that (a flat colour) would clip the history's own rounding, and the clip's shrink towards
  // the centre would move its brightness with it.
  float slack = max(max(hi.x, hi.y), max(hi.z, 1e-6)) / 1024.0;
  lo -= slack;
  hi += slack;
  // [blend]
  vec3 result = centre;
  if (!rejected) {
    vec3 history = to_space(u_filter == 1 ? catmull_rom(u_history, uv_then) : texture(u_history, uv_then).rgb);
    if (u_clip == 1) history = clamp(history, lo, hi);
    if (u_clip == 2) history = ycocg_to_rgb(clip_to_box(lo, hi, rgb_to_ycocg(history)));
    // A moving surface's history was resampled every frame and has blurred: this frame
    // weighs more the more it moved, up to a pixel a frame.
    result = mix(history, centre, mix(u_alpha, u_alpha_moving, clamp(moved, 0.0, 1.0)));
  }
  // [/blend]
  out_color = vec4(from_space(result), here.a);
  out_rejected = rejected ? 1.0 : 0.0;
}
